// kimp gui: start-up: the editor's buttons, the first scene, and the page's interface to the
// browser tests (window.kimpGui).
'use strict';

(function () {
  const {
    state, getJson, postJson, showTab, toYaml, fromYaml, formScene, sceneYaml, loadScene,
    clearErrors, showError, showProblems, loadCommand, startRun, initMotion, initParametric,
    openScene, completeSceneYaml, saveSession, readSession,
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
    document.getElementById('scene-export').addEventListener('click', async () => {
      const text = await completeSceneYaml(state.command, sceneYaml());
      const url = URL.createObjectURL(new Blob([text], { type: 'text/yaml' }));
      const a = el('a', { href: url, download: `${state.command}_scene.yaml` });
      document.body.appendChild(a);
      a.click();
      a.remove();
    });
    /** The form's scene as YAML, or null once its problems are shown. */
    const checkedSceneYaml = () => {
      const errors = [];
      const text = sceneYaml(errors);
      if (!errors.length) return text;
      showProblems(errors);
      return null;
    };
    document.getElementById('scene-validate').addEventListener('click', async () => {
      const text = checkedSceneYaml();
      if (text === null) return;
      const r = await postJson('/api/validate', { command: state.command, scene: text });
      if (r.ok) {
        clearErrors();
        document.getElementById('scene-error').textContent = 'scene is valid';
      } else showError(r.error);
    });
    const runOptions = () => ({
      name: document.getElementById('run-name').value.trim(),
      notes: document.getElementById('run-notes').value.trim(),
    });
    for (const id of ['run-name', 'run-notes']) document.getElementById(id).addEventListener('change', saveSession);
    document.getElementById('scene-run').addEventListener('click', async () => {
      const text = checkedSceneYaml();
      if (text === null) return;
      if (state.command !== 'sweep') {
        startRun(state.command, await completeSceneYaml(state.command, text), '', runOptions());
        return;
      }
      // A sweep runs on the scene last edited for its engine (saved as scene.yaml beside it).
      const engine = (formScene().engine || 'lumped').trim();
      const base = state.saved[engine];
      if (!base) {
        showError(`sweep: edit the ${engine} scene first (command ${engine}), then come back to sweep`);
        return;
      }
      startRun(
        'sweep',
        await completeSceneYaml(engine, base.yaml),
        toYaml(Object.assign(formScene(), { scene: 'scene.yaml' }), 0) + '\n',
        runOptions(),
      );
    });
    document.getElementById('run-cancel').addEventListener('click', () => {
      if (state.current) postJson(`/api/runs/${state.current}/cancel`, {});
    });
    await initMotion();
    await initParametric();
    await initExamples();
    await restoreSession();
    document.body.dataset.ready = '1';
  }

  /** The form as it was before a reload of the page (kept by saveSession in the browser). */
  async function restoreSession() {
    const s = readSession();
    if (!s || !s.saved) {
      state.restoring = false;
      return;
    }
    try {
      for (const [command, yaml] of Object.entries(s.saved))
        if (command !== state.command) state.saved[command] = { yaml: yaml, extra: {} };
      if (s.command && s.command !== state.command && state.info.commands.includes(s.command)) {
        document.getElementById('scene-command').value = s.command;
        await loadCommand(s.command);
      }
      if (s.saved[state.command]) loadScene(fromYaml(s.saved[state.command]));
      document.getElementById('run-name').value = s.name || '';
      document.getElementById('run-notes').value = s.notes || '';
      if (s.sweep) document.getElementById('sweep-yaml').value = s.sweep;
    } catch (e) {
      showError(`the previous session could not be restored: ${e.message}`);
    } finally {
      state.restoring = false;
    }
    if (s.tab && s.tab !== 'results') showTab(s.tab);
    if (s.tab === 'results' && s.shown) kimpGui.openResults(s.shown).catch(() => showTab('scene'));
  }

  // ---- the model before a run: buildings, walls and gaps drawn, periods listed ------------------
  let previewTimer = null;
  let previewAsked = 0;

  function previewModel() {
    clearTimeout(previewTimer);
    previewTimer = setTimeout(drawPreview, 300);
  }

  async function drawPreview() {
    const host = document.getElementById('scene-preview');
    if (state.command !== 'lumped') {
      host.innerHTML = '';
      const text = `The model is drawn for lumped scenes (not ${state.command}).`;
      host.appendChild(el('p', { class: 'muted', text: text }));
      return;
    }
    const asked = ++previewAsked;
    let m;
    try {
      // An invalid scene (being typed) is said by the validation, not by a refused request.
      const scene = sceneYaml();
      const valid = await postJson('/api/validate', { command: 'lumped', scene: scene });
      if (!valid.ok) throw new Error(valid.error);
      m = await postJson('/api/preview', { command: 'lumped', scene: scene });
    } catch (e) {
      if (asked !== previewAsked) return;
      host.innerHTML = '';
      host.appendChild(el('p', { class: 'run-error', text: e.message }));
      return;
    }
    if (asked !== previewAsked) return;
    host.innerHTML = '';
    host.appendChild(modelSvg(m));
    const fmt = kimp.fmt;
    const lines = [];
    const b = m.building;
    lines.push(
      `${b.kind === 'isolated' ? 'isolated' : 'fixed-base'} building, ${b.n_storeys} storeys, ` +
        `${fmt(b.masses.reduce((a, x) => a + x, 0) / 1e3, 4)} t, ` +
        `storey stiffness ${fmt(b.storey_stiffness / 1e6, 4)} MN/m`,
    );
    if (m.isolator)
      lines.push(
        `isolator ${m.isolator.kind}, initial stiffness ${fmt(m.isolator.initial_stiffness / 1e6, 4)} MN/m; ` +
          `isolated period ${fmt(m.isolated_period, 3)} s (${m.isolated_period_basis})`,
      );
    for (const x of m.buildings)
      lines.push(`${x.name}: periods ${x.periods.map((p) => fmt(p, 3)).join(', ')} s`);
    if (m.plan)
      lines.push(
        `in plan: ${m.plan.faces} wall faces, ${m.plan.damping} damping (ζ = ${fmt(100 * m.plan.damping_ratio, 3)} %` +
          `${m.plan.damping === 'modal' ? ' in every mode' : ' per direction'}), yielding faces: ` +
          `${m.plan.yielding_faces.length ? m.plan.yielding_faces.join(', ') : 'none'}`,
      );
    for (const c of m.contacts) lines.push(`contact ${c.name}: gap ${fmt(c.gap * 100, 4)} cm`);
    if (m.cases.length) lines.push(`cases: ${m.cases.join(', ')} (their overrides are not drawn)`);
    const list = el('ul', { class: 'preview-facts' });
    for (const l of lines) list.appendChild(el('li', { text: l }));
    host.appendChild(list);
    state.model = m;
  }

  /** The building (storeys as floors), the moat walls at their gaps and the neighbours, as SVG. */
  function modelSvg(m) {
    const NS = 'http://www.w3.org/2000/svg';
    const svg = document.createElementNS(NS, 'svg');
    const storey = 28;
    const n = m.building.n_storeys + (m.building.kind === 'isolated' ? 1 : 0);
    const nbMax = Math.max(m.neighbours.left.n_storeys, m.neighbours.right.n_storeys);
    const H = (Math.max(n, nbMax) + 1) * storey + 20;
    const W = 520;
    svg.setAttribute('viewBox', `0 0 ${W} ${H}`);
    svg.setAttribute('class', 'model-preview');
    const add = (tag, attrs, text) => {
      const e = document.createElementNS(NS, tag);
      for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
      if (text) e.textContent = text;
      svg.appendChild(e);
      return e;
    };
    const ground = H - 20;
    add('line', { x1: 0, y1: ground, x2: W, y2: ground, stroke: '#654', 'stroke-width': 3 });
    const x0 = 210;
    const bw = 100;
    // Gaps drawn at 200 px per metre (a 15 cm gap is 30 px), at least 6 px.
    const px = (g) => Math.max(6, g * 200);
    for (let i = 0; i < n; ++i) {
      const y = ground - (i + 1) * storey;
      add('rect', {
        x: x0,
        y: y,
        width: bw,
        height: storey - 4,
        fill: i === 0 && m.isolator ? '#cfe0f5' : '#e8ecf2',
        stroke: '#345',
      });
    }
    if (m.isolator)
      add('text', { x: x0 + bw / 2, y: ground - 8, 'text-anchor': 'middle', 'font-size': 10 }, 'isolator');
    for (const side of ['left', 'right']) {
      const w = m.walls[side];
      const sign = side === 'left' ? -1 : 1;
      if (w.present) {
        const x = side === 'left' ? x0 - px(w.gap) : x0 + bw + px(w.gap);
        add('rect', { x: x - (side === 'left' ? 8 : 0), y: ground - storey, width: 8, height: storey, fill: '#777' });
        add(
          'text',
          { x: x + sign * 4, y: ground + 14, 'text-anchor': 'middle', 'font-size': 10, class: 'gap-label' },
          `${kimp.fmt(w.gap * 100, 3)} cm`,
        );
      }
      const nb = m.neighbours[side];
      if (nb.present) {
        const x = side === 'left' ? x0 - px(nb.separation) - 110 : x0 + bw + px(nb.separation) + 10;
        for (let i = 0; i < nb.n_storeys; ++i)
          add('rect', {
            x: x, y: ground - (i + 1) * storey, width: 100, height: storey - 4, fill: '#f3efe6', stroke: '#865',
          });
      }
    }
    return svg;
  }

  /** The shipped scenes (data/scenes), each opened with the command whose schema knows its keys. */
  async function initExamples() {
    const select = document.getElementById('scene-example');
    for (const x of await getJson('/api/examples'))
      select.appendChild(el('option', { value: x.name, text: x.name.replace(/\.yaml$/, ''), title: x.about }));
    select.addEventListener('change', async () => {
      const name = select.value;
      if (!name) return;
      select.value = '';
      try {
        const r = await fetch('/assets/' + name);
        const text = await r.text();
        const keys = Object.keys(fromYaml(text));
        let command = null;
        for (const c of ['lumped', 'fem', 'study', 'collide'].filter((x) => state.info.commands.includes(x))) {
          const schema = state.schemas[c] || (state.schemas[c] = await getJson('/api/schema/' + c));
          if (keys.every((k) => schema.keys.some((x) => x.key === k))) {
            command = c;
            break;
          }
        }
        if (!command) throw new Error(`no command of this kimp reads ${name} (keys ${keys.join(', ')})`);
        await openScene(command, text);
        document.getElementById('run-name').value = name.replace(/\.yaml$/, '');
        saveSession();
      } catch (e) {
        showError(e.message);
      }
    });
  }

  kimpGui.previewModel = previewModel;

  // The interface to the browser tests: toYaml, fromYaml, sceneYaml, loadScene, startRun, state, ...
  window.kimpGui = kimpGui;
  init().catch((e) => {
    document.getElementById('scene-error').textContent = String(e);
  });
})();
