// kimp gui: scene editor generated from the scene schema, ground motions, background runs with
// progress (server-sent events), the parametric dialog, and results drawn by kimp.js.
'use strict';

(function () {
  const el = kimp.el;
  const state = { command: 'lumped', schema: null, schemas: {}, extra: {}, saved: {}, current: null, info: {} };

  // ---- server access -----------------------------------------------------------------------
  async function getJson(url) {
    const r = await fetch(url);
    const body = await r.json();
    if (!r.ok) throw new Error(body.error || r.statusText);
    return body;
  }

  async function postJson(url, value) {
    const r = await fetch(url, {
      method: 'POST',
      headers: { 'Content-Type': 'application/json', 'X-Kimp-Request': '1' },
      body: JSON.stringify(value),
    });
    const body = await r.json();
    if (!r.ok) throw new Error(body.error || r.statusText);
    return body;
  }

  // ---- tabs --------------------------------------------------------------------------------
  function showTab(name) {
    for (const b of document.querySelectorAll('header.top nav button'))
      b.classList.toggle('active', b.dataset.tab === name);
    for (const p of document.querySelectorAll('.pane')) p.classList.toggle('active', p.id === 'pane-' + name);
    if (name === 'runs') refreshRuns();
    if (name === 'motion') showMotion();
  }

  // ---- YAML: written here (quantities quoted, block maps, flow lists), read by js-yaml ----------
  function yamlScalar(v) {
    if (v === null || v === undefined) return 'null';
    if (typeof v === 'boolean' || typeof v === 'number') return String(v);
    if (Array.isArray(v)) return '[' + v.map(yamlScalar).join(', ') + ']';
    if (typeof v === 'object')
      return (
        '{' +
        Object.entries(v)
          .map(([k, x]) => `${yamlKey(k)}: ${yamlScalar(x)}`)
          .join(', ') +
        '}'
      );
    if (/^-?\d+(\.\d+)?([eE][-+]?\d+)?$/.test(v)) return v;
    return JSON.stringify(String(v));
  }

  function yamlKey(k) {
    return /^[A-Za-z0-9_][A-Za-z0-9_.\- ,]*$/.test(k) && !/ $/.test(k) ? k : JSON.stringify(k);
  }

  const isMap = (v) => v !== null && typeof v === 'object' && !Array.isArray(v);

  function toYaml(obj, indent) {
    const pad = ' '.repeat(indent || 0);
    const lines = [];
    for (const [k, v] of Object.entries(obj)) {
      if (isMap(v) && Object.keys(v).length) {
        lines.push(`${pad}${yamlKey(k)}:`);
        lines.push(toYaml(v, (indent || 0) + 2));
      } else if (Array.isArray(v) && v.length && v.every((item) => isMap(item) && Object.keys(item).length)) {
        lines.push(`${pad}${yamlKey(k)}:`);
        for (const item of v) {
          const inner = toYaml(item, (indent || 0) + 4).split('\n');
          inner[0] = pad + '  - ' + inner[0].trimStart();
          lines.push(inner.join('\n'));
        }
      } else lines.push(`${pad}${yamlKey(k)}: ${yamlScalar(v)}`);
    }
    return lines.filter((l) => l !== '').join('\n');
  }

  /** A scene's YAML text as an object (js-yaml: block scalars, anchors, flow maps and all). */
  function fromYaml(text) {
    const value = jsyaml.load(text);
    if (value === null || value === undefined) return {};
    if (typeof value !== 'object' || Array.isArray(value)) throw new Error('a scene is a map of keys (key: value)');
    return value;
  }

  /**
   * Keys of `obj` that the schema does not know, as the CLI names them ("unknown key 'gapz' in
   * walls.left (known: present, gap, ...)"): [{path, message}]. Maps take any key; list items are
   * checked against their item's keys.
   */
  function unknownKeys(obj, keys, where, out) {
    if (!obj || typeof obj !== 'object' || Array.isArray(obj) || !keys) return out;
    for (const [name, value] of Object.entries(obj)) {
      const k = keys.find((x) => x.key === name);
      const path = where ? `${where}.${name}` : name;
      if (!k) {
        out.push({
          path: where,
          message:
            `unknown key '${name}' in ${where || 'the scene'} ` + `(known: ${keys.map((x) => x.key).join(', ')})`,
        });
      } else if (k.keys) unknownKeys(value, k.keys, path, out);
      else if (k.type === 'list' && Array.isArray(value) && Array.isArray(k.item)) {
        value.forEach((item, i) => unknownKeys(item, k.item, `${path}[${i}]`, out));
      }
    }
    return out;
  }

  /** The part of `obj` the form cannot hold (unknown keys), kept so that a run refuses it too. */
  function unknownPart(obj, keys) {
    const extra = {};
    for (const [name, value] of Object.entries(obj || {})) {
      const k = keys.find((x) => x.key === name);
      if (!k) extra[name] = value;
      else if (k.keys && value && typeof value === 'object' && !Array.isArray(value)) {
        const inner = unknownPart(value, k.keys);
        if (Object.keys(inner).length) extra[name] = inner;
      }
    }
    return extra;
  }

  function mergeInto(target, extra) {
    for (const [k, v] of Object.entries(extra)) {
      if (v && typeof v === 'object' && !Array.isArray(v) && target[k] && typeof target[k] === 'object')
        mergeInto(target[k], v);
      else target[k] = v;
    }
    return target;
  }

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
    else input.value = value === undefined ? '' : Array.isArray(value) ? value.join(', ') : String(value);
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

  // ---- runs --------------------------------------------------------------------------------
  async function startRun(command, scene, sweep) {
    clearErrors();
    let id;
    try {
      id = (await postJson('/api/runs', { command: command, scene: scene, sweep: sweep })).id;
    } catch (e) {
      showError(e.message);
      return null;
    }
    const bar = document.getElementById('run-progress');
    const status = document.getElementById('run-status');
    const log = document.getElementById('run-log');
    log.textContent = '';
    status.textContent = `${id}: running`;
    status.dataset.state = 'running';
    bar.value = 0;
    state.current = id;
    return new Promise((resolve) => {
      const events = new EventSource(`/api/runs/${id}/events`);
      events.onmessage = async (m) => {
        const s = JSON.parse(m.data);
        bar.value = s.progress || 0;
        for (const line of s.log || []) log.textContent += line + '\n';
        log.scrollTop = log.scrollHeight;
        let note = '';
        if (s.state === 'queued') note = ` (place ${s.queue_position} in the queue)`;
        else if (s.state === 'running' && s.progress_text) note = ` (${s.progress_text})`;
        status.textContent = `${id}: ${s.state}${note}`;
        status.dataset.state = s.state;
        if (s.state !== 'running' && s.state !== 'queued') {
          events.close();
          if (s.state === 'done') await openResults(id);
          else if (s.error) showError(s.error);
          resolve(s.state);
        }
      };
      events.onerror = () => {
        events.close();
        resolve('lost');
      };
    });
  }

  /** The run's warnings (its log's "warning:" lines), e.g. why a sweep wrote no d_SRSS table. */
  async function runWarnings(id) {
    const r = await fetch(`/api/files/${id}/run.log`);
    if (!r.ok) return [];
    return (await r.text())
      .split('\n')
      .filter((l) => l.startsWith('warning: '))
      .map((l) => l.slice(9));
  }

  async function openResults(id, overlay) {
    const data = await getJson(`/api/runs/${id}/data`);
    data.title = id;
    const others = [];
    for (const o of overlay || []) {
      const d = await getJson(`/api/runs/${o}/data`);
      d.title = o;
      others.push(d);
    }
    const pane = document.getElementById('results');
    state.shown = { id: id, overlay: overlay || [] };
    kimp.showResults(pane, data, others);
    pane.insertBefore(
      el('p', {}, [el('a', { href: `/api/runs/${id}/report`, download: `${id}.html`, text: 'download report.html' })]),
      pane.children[1],
    );
    showTab('results');
    await Promise.all([runPicker(id, data, overlay || []), showRunNotes(id, data)]);
  }

  async function showRunNotes(id, data) {
    const host = document.getElementById('results-notes');
    host.innerHTML = '';
    const warnings = await runWarnings(id);
    const csv = data.csv || {};
    const gapStudy = data.kind === 'sweep' && Object.keys(csv).includes('sweep.csv') && !csv['dsrss_table.csv'];
    const dsrss = warnings.filter((w) => /d_SRSS/.test(w));
    if (gapStudy && dsrss.length) {
      host.appendChild(
        el('div', { class: 'notice dsrss-missing', text: `No d_req / d_SRSS table: ${dsrss.join('\n')}` }),
      );
    }
    const rest = warnings.filter((w) => !dsrss.includes(w));
    if (rest.length)
      host.appendChild(el('div', { class: 'notice run-warnings', text: `warnings of ${id}:\n${rest.join('\n')}` }));
  }

  /** Other finished runs of the same command to overlay on the charts (legend: run: case). */
  async function runPicker(id, data, overlay) {
    const host = document.getElementById('results-bar');
    host.innerHTML = '';
    const list = (await getJson('/api/runs')).filter(
      (r) => r.state === 'done' && r.id !== id && r.command === data.kind,
    );
    if (!list.length) return;
    const boxes = list.map((r) => {
      const box = el('input', { type: 'checkbox', value: r.id, class: 'overlay-run' });
      box.checked = overlay.includes(r.id);
      return el('label', {}, [box, document.createTextNode(' ' + r.id)]);
    });
    const go = el('button', { class: 'overlay-apply', text: 'Overlay on the charts' });
    go.addEventListener('click', () => {
      const chosen = Array.from(host.querySelectorAll('.overlay-run:checked')).map((b) => b.value);
      openResults(id, chosen);
    });
    host.appendChild(
      el('div', { class: 'section run-picker' }, [
        el('strong', { text: `Overlay other ${data.kind} runs:` }),
        ...boxes,
        go,
      ]),
    );
  }

  async function refreshRuns() {
    const list = await getJson('/api/runs');
    const host = document.getElementById('runs-list');
    host.innerHTML = '';
    const t = el('table', { class: 'data' });
    t.appendChild(
      el(
        'tr',
        {},
        ['run', 'command', 'state', ''].map((h) => el('th', { text: h })),
      ),
    );
    for (const r of list) {
      const actions = el('span');
      if (r.state === 'done') actions.appendChild(el('button', { text: 'results', onclick: () => openResults(r.id) }));
      if (r.state === 'running' || r.state === 'queued')
        actions.appendChild(
          el('button', { text: 'cancel', onclick: () => postJson(`/api/runs/${r.id}/cancel`, {}).then(refreshRuns) }),
        );
      // A cancelled or failed run: why, and what it wrote before it stopped.
      if (r.state !== 'done') {
        for (const f of (r.files || []).filter((x) => !x.endsWith('/')))
          actions.appendChild(el('a', { href: `/api/files/${r.id}/${f}`, text: f.slice(4) + ' ' }));
      }
      t.appendChild(
        el('tr', {}, [
          el('td', { text: r.id }),
          el('td', { text: r.command || '' }),
          el('td', { text: r.state + (r.state !== 'done' && r.error ? ` (${r.error})` : '') }),
          el('td', {}, [actions]),
        ]),
      );
    }
    host.appendChild(t);
  }

  // ---- ground motion -----------------------------------------------------------------------
  // The scene's ground motion as the server loaded, scaled and trimmed it for the scene's run
  // (POST /api/motion, m/s²), the uploaded file and the serial of the latest request.
  const motion = { rec: null, file: null, serial: 0 };
  const TWO_COLUMN_UNITS = { g: 9.80665, 'm/s^2': 1, 'cm/s^2': 0.01 };
  const MOTION_KEYS = [
    ['motion-scale-to-pga', 'ground_motion.scale_to_pga'],
    ['motion-scale', 'ground_motion.scale'],
    ['motion-duration', 'ground_motion.duration'],
  ];

  function sceneInput(path) {
    return document.querySelector(`#scene-form input[data-path="${path}"], #scene-form select[data-path="${path}"]`);
  }

  function setSceneValue(path, value) {
    const input = sceneInput(path);
    if (input) {
      input.value = value;
      syncYaml();
    }
  }

  /**
   * Starts a motion request: the returned function tells whether it is still the latest, so that
   * a slow answer (the synthetic motion, a record) never replaces the one chosen after it.
   */
  function motionRequest() {
    const serial = ++motion.serial;
    return () => serial === motion.serial;
  }

  function integrate(a, dt) {
    const v = [0];
    for (let i = 1; i < a.length; ++i) v.push(v[i - 1] + 0.5 * (a[i - 1] + a[i]) * dt);
    return v;
  }

  function peakAt(xs) {
    let k = 0;
    for (let i = 1; i < xs.length; ++i) if (Math.abs(xs[i]) > Math.abs(xs[k])) k = i;
    return k;
  }

  function plotMotion() {
    const host = document.getElementById('motion-charts');
    const info = document.getElementById('motion-info');
    const out = document.getElementById('motion-error');
    host.innerHTML = '';
    info.textContent = '';
    out.textContent = '';
    const rec = motion.rec;
    if (!rec) return;
    const a = rec.acceleration;
    const t = a.map((_, i) => i * rec.dt);
    const v = integrate(a, rec.dt);
    const d = integrate(v, rec.dt);
    const [ia, iv, id] = [peakAt(a), peakAt(v), peakAt(d)];
    const pga = Math.abs(a[ia]) / 9.80665;
    const pgv = Math.abs(v[iv]) * 100;
    const pgd = Math.abs(d[id]) * 100;
    info.dataset.pga = String(pga);
    info.dataset.samples = String(a.length);
    info.textContent =
      `${rec.name}: dt = ${rec.dt} s, ${a.length} samples (${kimp.fmt(a.length * rec.dt, 6)} s), ` +
      `PGA = ${kimp.fmt(pga, 4)} g, PGV = ${kimp.fmt(pgv, 4)} cm/s, PGD = ${kimp.fmt(pgd, 4)} cm ` +
      '(as the run scales it)';
    const marker = (i, ys, label) => {
      const y = new Array(ys.length).fill(null);
      y[i] = ys[i];
      return { label: label, y: y, marker: true, color: '#d62728' };
    };
    const cm = (xs) => xs.map((x) => x * 100);
    for (const [what, ys, ylabel, symbol, peak, i, value] of [
      ['acceleration', a, 'acceleration (m/s²)', 'a_g', 'PGA', ia, `${kimp.fmt(pga, 4)} g`],
      ['velocity', cm(v), 'velocity (cm/s)', 'v_g', 'PGV', iv, `${kimp.fmt(pgv, 4)} cm/s`],
      ['displacement', cm(d), 'displacement (cm)', 'd_g', 'PGD', id, `${kimp.fmt(pgd, 4)} cm`],
    ]) {
      kimp.chart(host, {
        title: `${rec.name}: ground ${what}, ${peak} = ${value} at ${kimp.fmt(t[i], 4)} s`,
        xlabel: 'time (s)',
        ylabel: ylabel,
        x: t,
        height: 260,
        series: [{ label: symbol, y: ys }, marker(i, ys, `${peak} ${value}`)],
      });
    }
  }

  /**
   * The scene's ground motion (a record, an upload or the synthetic motion) is loaded, scaled and
   * trimmed by kimp as its run does: the page asks the server for it and draws nothing of its own
   * when the server cannot.
   */
  async function loadMotion() {
    const latest = motionRequest();
    motion.rec = null;
    if (!state.info.motion_preview) {
      document.getElementById('motion-charts').innerHTML = '';
      document.getElementById('motion-info').textContent =
        'The ground motion is loaded, scaled and trimmed (the synthetic near-fault motion generated) ' +
        'by kimp at run time; this kimp gui cannot draw it before a run.';
      return;
    }
    const r = await fetch('/api/motion', {
      method: 'POST',
      headers: { 'Content-Type': 'application/json', 'X-Kimp-Request': '1' },
      body: JSON.stringify({ command: state.command === 'sweep' ? 'lumped' : state.command, scene: sceneYaml() }),
    });
    const body = await r.json();
    if (!latest()) return;
    if (r.ok) {
      motion.rec = body;
      plotMotion();
    } else {
      const info = document.getElementById('motion-info');
      document.getElementById('motion-charts').innerHTML = '';
      info.textContent = '';
      delete info.dataset.pga;
      delete info.dataset.samples;
      document.getElementById('motion-error').textContent = body.error;
    }
  }

  async function uploadMotion() {
    const latest = motionRequest();
    const file = motion.file;
    const unit = document.getElementById('motion-unit').value;
    const at2 = /\.at2$/i.test(file.name);
    const r = await fetch('/api/upload?name=' + encodeURIComponent(file.name) + '&unit=' + TWO_COLUMN_UNITS[unit], {
      method: 'POST',
      headers: { 'X-Kimp-Request': '1', 'Content-Type': 'application/octet-stream' },
      body: await file.text(),
    });
    const body = await r.json();
    if (!latest()) return;
    document.getElementById('motion-error').textContent = r.ok ? '' : body.error;
    if (!r.ok) return;
    // The scene names the uploaded file and, for a two-column file, the unit of its column.
    setSceneValue('ground_motion.record', body.path);
    setSceneValue('ground_motion.record_unit', at2 ? '' : unit);
    const pick = document.getElementById('motion-record');
    let option = pick.querySelector('option[data-upload]');
    if (!option) {
      option = el('option', { 'data-upload': '1' });
      pick.appendChild(option);
    }
    option.value = body.path;
    option.textContent = `uploaded: ${file.name}${at2 ? '' : ' (' + unit + ')'}`;
    pick.value = body.path;
    await loadMotion();
  }

  /** The motion tab's scaling inputs mirror the scene's keys (both ways). */
  function syncMotionInputs() {
    for (const [id, path] of MOTION_KEYS) {
      const input = sceneInput(path);
      document.getElementById(id).value = input ? input.value : '';
    }
  }

  async function showMotion() {
    syncMotionInputs();
    const record = sceneInput('ground_motion.record') ? sceneInput('ground_motion.record').value.trim() : '';
    const pick = document.getElementById('motion-record');
    if (!record || record === 'synthetic') pick.value = 'synthetic';
    else if (Array.from(pick.options).some((o) => o.value === record)) pick.value = record;
    await loadMotion();
  }

  async function initMotion() {
    const pick = document.getElementById('motion-record');
    pick.appendChild(
      el('option', { value: 'synthetic', text: 'synthetic near-fault motion (ground_motion.synthetic)' }),
    );
    for (const name of await getJson('/api/records')) pick.appendChild(el('option', { value: name, text: name }));
    pick.addEventListener('change', async () => {
      if (pick.selectedOptions[0] && pick.selectedOptions[0].dataset.upload) return;
      motion.file = null;
      setSceneValue('ground_motion.record', pick.value === 'synthetic' ? '' : pick.value);
      setSceneValue('ground_motion.record_unit', '');
      await loadMotion();
    });
    document.getElementById('motion-upload').addEventListener('change', async (e) => {
      motion.file = e.target.files[0] || null;
      if (motion.file) await uploadMotion();
    });
    document.getElementById('motion-unit').addEventListener('change', async () => {
      if (motion.file && !/\.at2$/i.test(motion.file.name)) await uploadMotion();
    });
    for (const [id, path] of MOTION_KEYS) {
      document.getElementById(id).addEventListener('change', async (e) => {
        setSceneValue(path, e.target.value.trim());
        await loadMotion();
      });
    }
  }

  // ---- parametric dialog -------------------------------------------------------------------
  /** Scene keys a sweep can vary: quantities, integers and choices (impact.law). */
  function sweepableKeys(keys, out) {
    for (const k of keys) {
      if (k.keys) sweepableKeys(k.keys, out);
      else if (
        ['quantity', 'optional quantity', 'integer', 'choice', 'flag'].includes(k.type) &&
        !k.path.includes('[]')
      )
        out.push(k);
    }
    return out;
  }

  /** The sweep file of the dialog's rows; regenerated on every change, so a run never uses a stale one. */
  function makeSweep() {
    const rows = document.getElementById('param-rows');
    const lines = ['# parameter study made by kimp gui', 'scene: scene.yaml', 'combine: product'];
    const params = [];
    let gap = null;
    for (const row of rows.querySelectorAll('.param-row')) {
      const key = row.querySelector('.param-key').value;
      let keyText = key;
      if (key === 'walls.left.gap' && document.getElementById('param-both').checked)
        keyText = 'walls.left.gap, walls.right.gap';
      if (key.endsWith('.gap') && !gap) gap = key;
      if (row.querySelector('.param-mode').value === 'range') {
        const [f, t, s] = ['from', 'to', 'step'].map((n) => row.querySelector('.param-' + n).value.trim());
        params.push(`  ${keyText}: {from: ${JSON.stringify(f)}, to: ${JSON.stringify(t)}, step: ${JSON.stringify(s)}}`);
      } else {
        const picked = Array.from(row.querySelectorAll('.param-option:checked')).map((b) => b.value);
        const typed = row
          .querySelector('.param-values')
          .value.split(',')
          .map((v) => v.trim())
          .filter((v) => v);
        const values = picked.length ? picked : typed;
        params.push(`  ${keyText}: [${values.map((v) => JSON.stringify(v)).join(', ')}]`);
      }
    }
    if (gap) lines.push('report:', '  kind: gap_study', `  gap: ${gap}`, '  title: "Gap sweep (kimp gui)"');
    lines.push('parameters:', ...params);
    document.getElementById('sweep-yaml').value = lines.join('\n') + '\n';
  }

  function addParamRow(path, mode, values) {
    const rows = document.getElementById('param-rows');
    const keys = sweepableKeys(state.schemas.lumped ? state.schemas.lumped.keys : [], []);
    const sel = el(
      'select',
      { class: 'param-key' },
      keys.map((k) =>
        el('option', {
          value: k.path,
          text: `${k.path}${k.unit ? ' [' + k.unit + ']' : ''}${k.type === 'choice' ? ' (choice)' : ''}`,
        }),
      ),
    );
    if (path) sel.value = path;
    const modeSel = el('select', { class: 'param-mode' }, [
      el('option', { value: 'range', text: 'from / to / step' }),
      el('option', { value: 'values', text: 'list of values' }),
    ]);
    const range = ['from', 'to', 'step'].map((n) => el('input', { type: 'text', class: 'param-' + n, placeholder: n }));
    const list = el('input', {
      type: 'text',
      class: 'param-values',
      placeholder: 'values, comma separated ("0.5, 0.7, 0.9")',
    });
    const options = el('span', { class: 'param-options' });
    const row = el('div', { class: 'controls param-row' }, [
      sel,
      modeSel,
      ...range,
      list,
      options,
      el('button', {
        text: '×',
        title: 'remove this parameter',
        onclick: () => {
          row.remove();
          makeSweep();
        },
      }),
    ]);
    const layout = () => {
      const k = keys.find((x) => x.path === sel.value) || {};
      const choice = k.type === 'choice' || k.type === 'flag';
      if (choice) modeSel.value = 'values';
      modeSel.disabled = choice;
      const isRange = modeSel.value === 'range';
      for (const input of range) input.style.display = isRange ? '' : 'none';
      list.style.display = !isRange && !choice ? '' : 'none';
      options.innerHTML = '';
      if (choice) {
        const opts = k.type === 'flag' ? ['false', 'true'] : k.options;
        for (const o of opts)
          options.appendChild(
            el('label', {}, [
              el('input', { type: 'checkbox', class: 'param-option', value: o }),
              document.createTextNode(' ' + o + ' '),
            ]),
          );
      }
    };
    sel.addEventListener('change', () => {
      layout();
      makeSweep();
    });
    modeSel.addEventListener('change', () => {
      layout();
      makeSweep();
    });
    row.addEventListener('input', makeSweep);
    row.addEventListener('change', makeSweep);
    if (mode) modeSel.value = mode;
    layout();
    if (mode === 'range' && values)
      range.forEach((input, i) => {
        input.value = values[i];
      });
    else if (values) {
      for (const b of options.querySelectorAll('.param-option')) b.checked = values.includes(b.value);
      list.value = values.join(', ');
    }
    rows.appendChild(row);
    makeSweep();
  }

  /** The lumped scene a dialog sweep runs on: the Scene tab's (or the last edited lumped one). */
  function lumpedSceneForSweep() {
    const yaml = state.command === 'lumped' ? sceneYaml() : state.saved.lumped ? state.saved.lumped.yaml : '';
    const scene = yaml.trim() ? fromYaml(yaml) : {};
    if (document.getElementById('param-companion').checked) {
      scene.integration = scene.integration || {};
      scene.integration.companion = true;
    }
    return toYaml(scene, 0) + '\n';
  }

  async function initParametric() {
    state.schemas.lumped = state.command === 'lumped' ? state.schema : await getJson('/api/schema/lumped');
    document.getElementById('param-add').addEventListener('click', () => addParamRow());
    document.getElementById('param-make').addEventListener('click', makeSweep);
    document.getElementById('param-both').addEventListener('change', makeSweep);
    document.getElementById('param-run').addEventListener('click', () => {
      const text = document.getElementById('sweep-yaml').value;
      startRun(
        'sweep',
        lumpedSceneForSweep(),
        text.trim() ? text : (makeSweep(), document.getElementById('sweep-yaml').value),
      );
    });
    addParamRow('walls.left.gap', 'range', ['10 cm', '20 cm', '5 cm']);
  }

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

  window.kimpGui = {
    toYaml: toYaml,
    fromYaml: fromYaml,
    sceneYaml: sceneYaml,
    loadScene: loadScene,
    startRun: startRun,
    state: state,
  };
  init().catch((e) => {
    document.getElementById('scene-error').textContent = String(e);
  });
})();
