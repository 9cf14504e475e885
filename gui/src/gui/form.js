// kimp gui: the scene form generated from the scene schema (inputs with units, sections, lists),
// its YAML view, loading a scene, and errors shown at the key they name.
'use strict';

(function () {
  const { state, getJson, toYaml, fromYaml, unknownKeys, unknownPart, mergeInto } = kimpGui;
  const el = kimp.el;

  // ---- the form ----------------------------------------------------------------------------
  function defaultText(k) {
    if (k.default === null || k.default === undefined) return '';
    return Array.isArray(k.default) ? k.default.join(', ') : String(k.default);
  }

  function fieldInput(k, onChange) {
    let input;
    if (k.type === 'choice') {
      input = el(
        'select',
        {},
        k.options.map((o) => el('option', { value: o, text: o })),
      );
      input.value = String(k.default);
    } else if (k.type === 'flag') {
      input = el('input', { type: 'checkbox' });
      input.checked = !!k.default;
    } else {
      input = el('input', { type: 'text', placeholder: defaultText(k) });
    }
    input.dataset.path = k.path;
    input.addEventListener('change', onChange);
    return input;
  }

  function readField(k, input) {
    if (k.type === 'choice') return input.value === String(k.default) ? undefined : input.value;
    if (k.type === 'flag') return input.checked === !!k.default ? undefined : input.checked;
    const v = input.value.trim();
    if (v === '') return undefined;
    if (k.type === 'integer') return Number(v);
    if (k.type === 'quantity_list') return v.split(',').map((s) => s.trim());
    return v;
  }

  function writeField(k, input, value) {
    if (k.type === 'flag') input.checked = value === undefined ? !!k.default : !!value;
    else if (k.type === 'choice') input.value = value === undefined ? String(k.default) : String(value);
    // null: not set (an optional key of a complete scene), as an empty field.
    else if (value === undefined || value === null) input.value = '';
    else input.value = Array.isArray(value) ? value.join(', ') : String(value);
  }

  const fields = [];

  function buildKeys(parent, keys, onChange) {
    for (const k of keys) {
      if (k.type === 'section' || k.type === 'optional section') {
        const fs = el('details', { class: 'form-section', 'data-path': k.path });
        fs.appendChild(el('summary', { text: `${k.key} — ${k.doc || ''}` }));
        if (
          k.path.split('.').length === 1 &&
          ['building', 'walls', 'impact', 'ground_motion', 'integration'].includes(k.key)
        )
          fs.open = true;
        buildKeys(fs, k.keys || [], onChange);
        parent.appendChild(fs);
      } else if (k.type === 'list' || k.type === 'map') {
        const area = el('textarea', {
          class: 'yaml list-yaml',
          'data-path': k.path,
          rows: 4,
          placeholder: `${k.key}: YAML (${k.doc})`,
        });
        area.addEventListener('change', onChange);
        const row = el('div', { class: 'field', 'data-path': k.path }, [
          el('label', { text: k.key }),
          area,
          el('span', { class: 'doc', text: k.doc || '' }),
        ]);
        parent.appendChild(row);
        fields.push({ key: k, input: area, row: row, raw: true });
      } else {
        const input = fieldInput(k, onChange);
        const unit = k.unit ? ` [${k.unit}]` : '';
        const range = k.range && k.range.text ? ` (${k.range.text})` : '';
        const row = el('div', { class: 'field', 'data-path': k.path }, [
          el('label', { text: k.key + unit, title: k.path }),
          input,
          el('span', { class: 'doc', text: (k.doc || '') + range }),
        ]);
        parent.appendChild(row);
        fields.push({ key: k, input: input, row: row });
      }
    }
  }

  function setPath(obj, path, value) {
    const parts = path.split('.');
    let o = obj;
    for (const p of parts.slice(0, -1)) o = o[p] = o[p] || {};
    o[parts[parts.length - 1]] = value;
  }

  function getPath(obj, path) {
    let o = obj;
    for (const p of path.split('.')) {
      if (!o || typeof o !== 'object') return undefined;
      o = o[p];
    }
    return o;
  }

  /** The scene of the form; YAML errors of the raw boxes (cases, laws) go to `errors`. */
  function formScene(errors) {
    const scene = {};
    for (const f of fields) {
      if (f.raw) {
        const t = f.input.value.trim();
        if (!t) continue;
        try {
          setPath(scene, f.key.path, jsyaml.load(t));
        } catch (e) {
          if (errors) errors.push({ path: f.key.path, message: `${f.key.path}: ${e.message}` });
        }
        continue;
      }
      const v = readField(f.key, f.input);
      if (v !== undefined) setPath(scene, f.key.path, v);
    }
    return mergeInto(scene, JSON.parse(JSON.stringify(state.extra || {})));
  }

  function sceneYaml(errors) {
    return toYaml(formScene(errors), 0) + '\n';
  }

  /** `scene` over `defaults`: maps merged key by key, anything else (lists, values) the scene's. */
  function overDefaults(defaults, scene) {
    const out = JSON.parse(JSON.stringify(defaults));
    for (const [k, v] of Object.entries(scene)) {
      const isMap = (x) => x && typeof x === 'object' && !Array.isArray(x);
      out[k] = isMap(v) && isMap(out[k]) ? overDefaults(out[k], v) : v;
    }
    return out;
  }

  /**
   * The complete scene a run saves: every key of the command's defaults (`--print-defaults`,
   * which reads back to the same values) with the form's values over them, so that the saved
   * scene does not depend on the defaults of the version that reads it. A sweep file has no
   * defaults (its parameters are the user's): it stays as written.
   */
  async function completeSceneYaml(command, yaml) {
    if (command === 'sweep') return yaml;
    if (!state.defaults) state.defaults = {};
    if (!state.defaults[command]) {
      const r = await fetch('/api/defaults/' + command);
      if (!r.ok) return yaml;
      state.defaults[command] = fromYaml(await r.text());
    }
    return toYaml(overDefaults(state.defaults[command], fromYaml(yaml)), 0) + '\n';
  }

  // ---- the session: the form's state kept in the browser across a reload -----------------------
  const SESSION = 'kimp-gui-session';

  function saveSession() {
    if (!state.schema || state.restoring) return;
    try {
      const saved = {};
      for (const [k, v] of Object.entries(state.saved)) saved[k] = v.yaml;
      saved[state.command] = sceneYaml();
      const tab = document.querySelector('header.top nav button.active');
      localStorage.setItem(
        SESSION,
        JSON.stringify({
          command: state.command,
          saved: saved,
          name: document.getElementById('run-name').value,
          notes: document.getElementById('run-notes').value,
          sweep: document.getElementById('sweep-yaml').value,
          tab: tab ? tab.dataset.tab : 'scene',
          shown: state.shown ? state.shown.id : null,
        }),
      );
    } catch {
      // No storage: the session is not kept.
    }
  }

  function readSession() {
    try {
      return JSON.parse(localStorage.getItem(SESSION) || 'null');
    } catch {
      return null;
    }
  }

  /** Fill the form from a scene object; its unknown keys are reported (and kept, as the CLI refuses them). */
  function loadScene(obj, source) {
    for (const f of fields) {
      const v = getPath(obj, f.key.path);
      if (f.raw)
        f.input.value =
          v === undefined
            ? ''
            : toYaml({ x: v }, 0)
                .split('\n')
                .slice(1)
                .map((l) => l.slice(2))
                .join('\n');
      else writeField(f.key, f.input, v);
    }
    state.extra = unknownPart(obj, state.schema.keys);
    syncYaml();
    const unknown = unknownKeys(obj, state.schema.keys, '', []);
    if (unknown.length) {
      showProblems(
        unknown.map((u) => ({ path: u.path, message: `${source ? source + ': ' : ''}${u.message}` })),
        `${unknown.length} unknown key(s): kept in the YAML, so Validate and Run refuse the scene as the CLI does ` +
          'until they are fixed (Scene as YAML below, then Apply).',
      );
    }
  }

  function syncYaml() {
    const errors = [];
    document.getElementById('scene-yaml').value = sceneYaml(errors);
    clearErrors();
    if (errors.length) showProblems(errors);
    saveSession();
    if (kimpGui.previewModel) kimpGui.previewModel();
  }

  function clearErrors() {
    for (const r of document.querySelectorAll('.error')) r.classList.remove('error');
    for (const e of document.querySelectorAll('.field-error')) e.remove();
    document.getElementById('scene-error').textContent = '';
  }

  /**
   * The form element a message's key path names: the field itself, else (a list item such as
   * cases[0].law) the list's box, else the nearest section (walls.left for an unknown key there).
   */
  function elementOf(path) {
    const plain = path.replace(/\[\d*\]/g, '');
    const candidates = [plain];
    if (path.includes('[')) candidates.push(path.slice(0, path.indexOf('[')));
    for (let p = plain; p.includes('.');) {
      p = p.slice(0, p.lastIndexOf('.'));
      candidates.push(p);
    }
    for (const c of candidates) {
      const e = document.querySelector(`#scene-form .field[data-path="${c}"], #scene-form details[data-path="${c}"]`);
      if (e) return e;
    }
    return null;
  }

  function flagAt(path, text) {
    const target = elementOf(path);
    if (!target) return false;
    target.classList.add('error');
    const note = el('div', { class: 'field-error', text: text });
    if (target.tagName === 'DETAILS') target.insertBefore(note, target.children[1] || null);
    else target.appendChild(note);
    for (let p = target; p; p = p.parentElement) if (p.tagName === 'DETAILS') p.open = true;
    return true;
  }

  /** Key path named by a message line of the CLI, or null. */
  function pathOf(line) {
    const unknown = /unknown key '([^']+)' in ([A-Za-z0-9_.[\]]+)/.exec(line);
    if (unknown) return unknown[2];
    const m = /^[^:]*:\d+: ([A-Za-z0-9_.[\]]+)[ :=]/.exec(line) || /key "?([A-Za-z0-9_.[\]]+)"?/.exec(line);
    return m ? m[1] : null;
  }

  /** The command's own message, also shown at each field it names ("file:line: key.path = ..."). */
  function showError(message) {
    clearErrors();
    document.getElementById('scene-error').textContent = message;
    for (const line of message.split('\n')) {
      const path = pathOf(line);
      if (path) flagAt(path, line);
    }
  }

  /** Problems found on the page ([{path, message}]) at their fields, and listed above the form. */
  function showProblems(problems, summary) {
    const box = document.getElementById('scene-error');
    box.textContent = (summary ? summary + '\n' : '') + problems.map((p) => p.message).join('\n');
    for (const p of problems) flagAt(p.path, p.message);
  }

  /** Open the scene text `yaml` of `command` in the editor (an example, a past run's scene). */
  async function openScene(command, yaml) {
    const select = document.getElementById('scene-command');
    if (command !== state.command) {
      select.value = command;
      await loadCommand(command);
    }
    loadScene(fromYaml(yaml));
  }

  async function loadCommand(command) {
    if (state.schema) state.saved[state.command] = { yaml: sceneYaml(), extra: state.extra };
    state.command = command;
    state.schema = await getJson('/api/schema/' + command);
    state.extra = {};
    fields.length = 0;
    const form = document.getElementById('scene-form');
    form.innerHTML = '';
    buildKeys(form, state.schema.keys, syncYaml);
    const saved = state.saved[command];
    if (saved) loadScene(fromYaml(saved.yaml));
    else syncYaml();
  }

  Object.assign(kimpGui, {
    formScene, sceneYaml, loadScene, syncYaml, clearErrors, showError, showProblems,
    loadCommand, openScene, completeSceneYaml, saveSession, readSession,
  });
})();
