// kimp gui: start-up: the editor's buttons, the first scene, and the page's interface to the
// browser tests (window.kimpGui).
'use strict';

(function () {
  const {
    state, getJson, postJson, showTab, toYaml, fromYaml, formScene, sceneYaml, loadScene,
    clearErrors, showError, showProblems, loadCommand, startRun, initMotion, initParametric,
  } = kimpGui;
  const el = kimp.el;

  // ---- start -------------------------------------------------------------------------------
  async function init() {
    for (const b of document.querySelectorAll('header.top nav button'))
      b.addEventListener('click', () => showTab(b.dataset.tab));
    const info = await getJson('/api/info');
    state.info = info;
    document.getElementById('version').textContent = info.version;
    const cmd = document.getElementById('scene-command');
    for (const c of info.commands) cmd.appendChild(el('option', { value: c, text: c }));
    cmd.addEventListener('change', () => loadCommand(cmd.value));
    await loadCommand('lumped');
    document.getElementById('scene-apply').addEventListener('click', () => {
      try {
        loadScene(fromYaml(document.getElementById('scene-yaml').value));
      } catch (e) {
        showError(e.message);
      }
    });
    document.getElementById('scene-import').addEventListener('change', async (e) => {
      const f = e.target.files[0];
      if (!f) return;
      try {
        loadScene(fromYaml(await f.text()), f.name);
      } catch (err) {
        showError(`${f.name}: ${err.message}`);
      }
    });
    document.getElementById('scene-export').addEventListener('click', () => {
      const url = URL.createObjectURL(new Blob([sceneYaml()], { type: 'text/yaml' }));
      const a = el('a', { href: url, download: `${state.command}_scene.yaml` });
      document.body.appendChild(a);
      a.click();
      a.remove();
    });
    document.getElementById('scene-validate').addEventListener('click', async () => {
      const errors = [];
      const text = sceneYaml(errors);
      if (errors.length) {
        showProblems(errors);
        return;
      }
      const r = await postJson('/api/validate', { command: state.command, scene: text });
      if (r.ok) {
        clearErrors();
        document.getElementById('scene-error').textContent = 'scene is valid';
      } else showError(r.error);
    });
    document.getElementById('scene-run').addEventListener('click', () => {
      const errors = [];
      const text = sceneYaml(errors);
      if (errors.length) {
        showProblems(errors);
        return;
      }
      if (state.command !== 'sweep') {
        startRun(state.command, text, '');
        return;
      }
      // A sweep runs on the scene last edited for its engine (saved as scene.yaml beside it).
      const engine = (formScene().engine || 'lumped').trim();
      const base = state.saved[engine];
      if (!base) {
        showError(`sweep: edit the ${engine} scene first (command ${engine}), then come back to sweep`);
        return;
      }
      startRun('sweep', base.yaml, toYaml(Object.assign(formScene(), { scene: 'scene.yaml' }), 0) + '\n');
    });
    document.getElementById('run-cancel').addEventListener('click', () => {
      if (state.current) postJson(`/api/runs/${state.current}/cancel`, {});
    });
    await initMotion();
    await initParametric();
    document.body.dataset.ready = '1';
  }

  // The interface to the browser tests: toYaml, fromYaml, sceneYaml, loadScene, startRun, state, ...
  window.kimpGui = kimpGui;
  init().catch((e) => {
    document.getElementById('scene-error').textContent = String(e);
  });
})();
