// kimp gui: scene editor generated from the scene schema, ground motions, background runs with
// progress (server-sent events), the parametric dialog, and results drawn by kimp.js.
'use strict';

(function () {
  const el = kimp.el;
  const state = { command: 'lumped', schema: null, values: {}, lists: {}, runs: {}, current: null };

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
    for (const b of document.querySelectorAll('header.top nav button')) b.classList.toggle('active', b.dataset.tab === name);
    for (const p of document.querySelectorAll('.pane')) p.classList.toggle('active', p.id === 'pane-' + name);
    if (name === 'runs') refreshRuns();
  }

  // ---- YAML (the subset scenes use: nested maps, lists of maps, flow lists, quoted scalars) ----
  function yamlScalar(v) {
    if (typeof v === 'boolean' || typeof v === 'number') return String(v);
    if (Array.isArray(v)) return '[' + v.map(yamlScalar).join(', ') + ']';
    if (/^-?\d+(\.\d+)?([eE][-+]?\d+)?$/.test(v)) return v;
    return JSON.stringify(String(v));
  }

  function toYaml(obj, indent) {
    const pad = ' '.repeat(indent || 0);
    const lines = [];
    for (const [k, v] of Object.entries(obj)) {
      if (v && typeof v === 'object' && !Array.isArray(v)) {
        lines.push(`${pad}${k}:`);
        lines.push(toYaml(v, (indent || 0) + 2));
      } else if (Array.isArray(v) && v.length && typeof v[0] === 'object') {
        lines.push(`${pad}${k}:`);
        for (const item of v) {
          const inner = toYaml(item, (indent || 0) + 4).split('\n');
          inner[0] = pad + '  - ' + inner[0].trimStart();
          lines.push(inner.join('\n'));
        }
      } else lines.push(`${pad}${k}: ${yamlScalar(v)}`);
    }
    return lines.filter((l) => l !== '').join('\n');
  }

  function parseScalar(text) {
    const t = text.trim();
    if (t.startsWith('"') || t.startsWith("'")) return t.slice(1, -1);
    if (t.startsWith('[')) return t.slice(1, -1).split(',').map((s) => parseScalar(s)).filter((s) => s !== '');
    if (t === 'true' || t === 'false') return t === 'true';
    return t;
  }

  function fromYaml(text) {
    const lines = text.split('\n').map((l) => l.replace(/\s+#.*$/, '').replace(/^#.*$/, '')).filter((l) => l.trim() !== '');
    let i = 0;
    function block(indent) {
      let result = null;
      while (i < lines.length) {
        const line = lines[i];
        const ind = line.length - line.trimStart().length;
        if (ind < indent) break;
        const body = line.trim();
        if (body.startsWith('- ')) {
          result = result || [];
          // A list item: its first key on the dash line, the rest indented below.
          lines[i] = ' '.repeat(ind + 2) + body.slice(2);
          result.push(block(ind + 2));
          continue;
        }
        const m = /^([^:]+):\s*(.*)$/.exec(body);
        if (!m) throw new Error(`line "${body}": expected key: value`);
        result = result || {};
        ++i;
        if (m[2] === '') result[m[1].trim()] = block(ind + 1) || {};
        else result[m[1].trim()] = parseScalar(m[2]);
      }
      return result;
    }
    return block(0) || {};
  }

  // ---- the form ----------------------------------------------------------------------------
  function defaultText(k) {
    if (k.default === null || k.default === undefined) return '';
    return Array.isArray(k.default) ? k.default.join(', ') : String(k.default);
  }

  function fieldInput(k, onChange) {
    let input;
    if (k.type === 'choice') {
      input = el('select', {}, k.options.map((o) => el('option', { value: o, text: o })));
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
        if (k.path.split('.').length === 1 && ['building', 'walls', 'impact', 'ground_motion', 'integration'].includes(k.key)) fs.open = true;
        buildKeys(fs, k.keys || [], onChange);
        parent.appendChild(fs);
      } else if (k.type === 'list' || k.type === 'map') {
        const area = el('textarea', { class: 'yaml list-yaml', 'data-path': k.path, rows: 4, placeholder: `${k.key}: YAML (${k.doc})` });
        area.addEventListener('change', onChange);
        const row = el('div', { class: 'field', 'data-path': k.path }, [el('label', { text: k.key }), area, el('span', { class: 'doc', text: k.doc || '' })]);
        parent.appendChild(row);
        fields.push({ key: k, input: area, row: row, raw: true });
      } else {
        const input = fieldInput(k, onChange);
        const unit = k.unit ? ` [${k.unit}]` : '';
        const range = k.range && k.range.text ? ` (${k.range.text})` : '';
        const row = el('div', { class: 'field', 'data-path': k.path }, [
          el('label', { text: k.key + unit, title: k.path }), input, el('span', { class: 'doc', text: (k.doc || '') + range }),
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

  function formScene() {
    const scene = {};
    for (const f of fields) {
      if (f.raw) {
        const t = f.input.value.trim();
        if (t) setPath(scene, f.key.path, fromYaml(`x:\n${t.split('\n').map((l) => '  ' + l).join('\n')}`).x);
        continue;
      }
      const v = readField(f.key, f.input);
      if (v !== undefined) setPath(scene, f.key.path, v);
    }
    return scene;
  }

  function sceneYaml() {
    return toYaml(formScene(), 0) + '\n';
  }

  function loadScene(obj) {
    for (const f of fields) {
      const v = getPath(obj, f.key.path);
      if (f.raw) f.input.value = v === undefined ? '' : toYaml({ x: v }, 0).split('\n').slice(1).map((l) => l.slice(2)).join('\n');
      else writeField(f.key, f.input, v);
    }
    syncYaml();
  }

  function syncYaml() {
    document.getElementById('scene-yaml').value = sceneYaml();
    clearErrors();
  }

  function clearErrors() {
    for (const r of document.querySelectorAll('.field.error')) r.classList.remove('error');
    for (const e of document.querySelectorAll('.field-error')) e.remove();
    document.getElementById('scene-error').textContent = '';
  }

  /** The command's own message, also shown at each field it names ("file:line: key.path = ..."). */
  function showError(message) {
    clearErrors();
    document.getElementById('scene-error').textContent = message;
    for (const line of message.split('\n')) {
      const m = /^[^:]*:\d+: ([A-Za-z0-9_.]+)(\[\d+\])?[ :]/.exec(line) || /key "?([A-Za-z0-9_.]+)"?/.exec(line);
      if (!m) continue;
      const row = document.querySelector(`.field[data-path="${m[1]}"]`);
      if (!row) continue;
      row.classList.add('error');
      row.appendChild(el('div', { class: 'field-error', text: line }));
      let p = row.parentElement;
      while (p) { if (p.tagName === 'DETAILS') p.open = true; p = p.parentElement; }
    }
  }

  async function loadCommand(command) {
    state.command = command;
    state.schema = await getJson('/api/schema/' + command);
    fields.length = 0;
    const form = document.getElementById('scene-form');
    form.innerHTML = '';
    buildKeys(form, state.schema.keys, syncYaml);
    syncYaml();
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
    bar.value = 0;
    state.current = id;
    return new Promise((resolve) => {
      const events = new EventSource(`/api/runs/${id}/events`);
      events.onmessage = async (m) => {
        const s = JSON.parse(m.data);
        bar.value = s.progress || 0;
        for (const line of s.log || []) log.textContent += line + '\n';
        log.scrollTop = log.scrollHeight;
        status.textContent = `${id}: ${s.state}`;
        status.dataset.state = s.state;
        if (s.state !== 'running' && s.state !== 'queued') {
          events.close();
          if (s.state === 'done') await openResults(id);
          else if (s.error) showError(s.error);
          resolve(s.state);
        }
      };
      events.onerror = () => { events.close(); resolve('lost'); };
    });
  }

  async function openResults(id) {
    const data = await getJson(`/api/runs/${id}/data`);
    data.title = id;
    const pane = document.getElementById('results');
    kimp.showResults(pane, data);
    pane.insertBefore(el('p', {}, [el('a', { href: `/api/runs/${id}/report`, download: `${id}.html`, text: 'download report.html' })]), pane.children[1]);
    showTab('results');
  }

  async function refreshRuns() {
    const list = await getJson('/api/runs');
    const host = document.getElementById('runs-list');
    host.innerHTML = '';
    const t = el('table', { class: 'data' });
    t.appendChild(el('tr', {}, ['run', 'command', 'state', ''].map((h) => el('th', { text: h }))));
    for (const r of list) {
      const actions = el('span');
      if (r.state === 'done') actions.appendChild(el('button', { text: 'results', onclick: () => openResults(r.id) }));
      if (r.state === 'running') actions.appendChild(el('button', { text: 'cancel', onclick: () => postJson(`/api/runs/${r.id}/cancel`, {}).then(refreshRuns) }));
      t.appendChild(el('tr', {}, [el('td', { text: r.id }), el('td', { text: r.command || '' }), el('td', { text: r.state }), el('td', {}, [actions])]));
    }
    host.appendChild(t);
  }

  // ---- ground motion -----------------------------------------------------------------------
  function integrate(a, dt) {
    const v = [0];
    for (let i = 1; i < a.length; ++i) v.push(v[i - 1] + 0.5 * (a[i - 1] + a[i]) * dt);
    return v;
  }

  function plotMotion(rec) {
    const host = document.getElementById('motion-charts');
    host.innerHTML = '';
    const scale = Number(document.querySelector('[data-path="ground_motion.scale"]')?.value || 1) || 1;
    const durationText = document.querySelector('[data-path="ground_motion.duration"]')?.value || '';
    const duration = parseFloat(durationText) || rec.duration;
    const n = Math.min(rec.acceleration.length, Math.round(duration / rec.dt) + 1);
    const a = rec.acceleration.slice(0, n).map((x) => x * scale);
    const t = a.map((_, i) => i * rec.dt);
    const v = integrate(a, rec.dt);
    const d = integrate(v, rec.dt);
    const peak = (xs) => Math.max(...xs.map(Math.abs));
    host.appendChild(el('p', { text: `${rec.name}: dt = ${rec.dt} s, ${n} samples, PGA = ${kimp.fmt(peak(a) / 9.80665, 4)} g, ` +
      `PGV = ${kimp.fmt(peak(v) * 100, 4)} cm/s, PGD = ${kimp.fmt(peak(d) * 100, 4)} cm (scale ${scale})` }));
    kimp.chart(host, { title: `${rec.name}: ground acceleration`, xlabel: 'time (s)', ylabel: 'acceleration (m/s²)', x: t, series: [{ label: 'a_g', y: a }], height: 200 });
    kimp.chart(host, { title: `${rec.name}: ground velocity`, xlabel: 'time (s)', ylabel: 'velocity (m/s)', x: t, series: [{ label: 'v_g', y: v }], height: 200 });
    kimp.chart(host, { title: `${rec.name}: ground displacement`, xlabel: 'time (s)', ylabel: 'displacement (m)', x: t, series: [{ label: 'd_g', y: d }], height: 200 });
  }

  function setRecord(value) {
    const input = document.querySelector('input[data-path="ground_motion.record"]');
    if (input) { input.value = value; syncYaml(); }
  }

  async function initMotion() {
    const pick = document.getElementById('motion-record');
    pick.appendChild(el('option', { value: 'synthetic', text: 'synthetic near-fault motion (generated at run time)' }));
    for (const name of await getJson('/api/records')) pick.appendChild(el('option', { value: name, text: name }));
    pick.addEventListener('change', async () => {
      setRecord(pick.value === 'synthetic' ? '' : pick.value);
      document.getElementById('motion-charts').innerHTML = '';
      if (pick.value !== 'synthetic') plotMotion(await getJson('/api/records/' + encodeURIComponent(pick.value)));
    });
    document.getElementById('motion-upload').addEventListener('change', async (e) => {
      const file = e.target.files[0];
      if (!file) return;
      const r = await fetch('/api/upload?name=' + encodeURIComponent(file.name) + '&unit=' + document.getElementById('motion-unit').value,
        { method: 'POST', headers: { 'X-Kimp-Request': '1', 'Content-Type': 'application/octet-stream' }, body: await file.text() });
      const body = await r.json();
      const out = document.getElementById('motion-error');
      out.textContent = r.ok ? '' : body.error;
      if (r.ok) { setRecord(body.path); plotMotion(body); }
    });
  }

  // ---- parametric dialog -------------------------------------------------------------------
  function quantityPaths(keys, out) {
    for (const k of keys) {
      if (k.keys) quantityPaths(k.keys, out);
      else if (['quantity', 'optional quantity', 'integer'].includes(k.type) && !k.path.includes('[]')) out.push(k);
    }
    return out;
  }

  function initParametric() {
    const rows = document.getElementById('param-rows');
    const addRow = (path, from, to, step) => {
      const keys = quantityPaths(state.schema ? state.schema.keys : [], []);
      const sel = el('select', { class: 'param-key' }, keys.map((k) => el('option', { value: k.path, text: `${k.path}${k.unit ? ' [' + k.unit + ']' : ''}` })));
      if (path) sel.value = path;
      const inputs = [from, to, step].map((v, i) => el('input', { type: 'text', class: 'param-' + ['from', 'to', 'step'][i], value: v || '', placeholder: ['from', 'to', 'step'][i] }));
      rows.appendChild(el('div', { class: 'controls param-row' }, [sel, ...inputs, el('button', { text: '×', onclick: (e) => { e.target.parentElement.remove(); } })]));
    };
    document.getElementById('param-add').addEventListener('click', () => addRow());
    document.getElementById('param-make').addEventListener('click', () => {
      const lines = ['# parameter study made by kimp gui', 'scene: scene.yaml', 'combine: product'];
      const params = [];
      let gap = null;
      for (const row of rows.querySelectorAll('.param-row')) {
        const key = row.querySelector('.param-key').value;
        let keyText = key;
        if (key === 'walls.left.gap' && document.getElementById('param-both').checked) keyText = 'walls.left.gap, walls.right.gap';
        if (key.endsWith('.gap') && !gap) gap = key;
        const [f, t, s] = ['from', 'to', 'step'].map((n) => row.querySelector('.param-' + n).value.trim());
        params.push(`  ${keyText}: {from: ${JSON.stringify(f)}, to: ${JSON.stringify(t)}, step: ${JSON.stringify(s)}}`);
      }
      if (gap) lines.push('report:', '  kind: gap_study', `  gap: ${gap}`, '  title: "Gap sweep (kimp gui)"');
      lines.push('parameters:', ...params);
      document.getElementById('sweep-yaml').value = lines.join('\n') + '\n';
    });
    document.getElementById('param-run').addEventListener('click', () => {
      if (!document.getElementById('sweep-yaml').value.trim()) document.getElementById('param-make').click();
      startRun('sweep', sceneYaml(), document.getElementById('sweep-yaml').value);
    });
    addRow('walls.left.gap', '10 cm', '20 cm', '5 cm');
  }

  // ---- start -------------------------------------------------------------------------------
  async function init() {
    for (const b of document.querySelectorAll('header.top nav button')) b.addEventListener('click', () => showTab(b.dataset.tab));
    const info = await getJson('/api/info');
    document.getElementById('version').textContent = info.version;
    const cmd = document.getElementById('scene-command');
    for (const c of info.commands.filter((x) => x !== 'sweep')) cmd.appendChild(el('option', { value: c, text: c }));
    cmd.addEventListener('change', () => loadCommand(cmd.value));
    await loadCommand('lumped');
    document.getElementById('scene-apply').addEventListener('click', () => {
      try { loadScene(fromYaml(document.getElementById('scene-yaml').value)); } catch (e) { showError(e.message); }
    });
    document.getElementById('scene-import').addEventListener('change', async (e) => {
      const f = e.target.files[0];
      if (!f) return;
      try { loadScene(fromYaml(await f.text())); } catch (err) { showError(`${f.name}: ${err.message}`); }
    });
    document.getElementById('scene-export').addEventListener('click', () => {
      const url = URL.createObjectURL(new Blob([sceneYaml()], { type: 'text/yaml' }));
      const a = el('a', { href: url, download: `${state.command}_scene.yaml` });
      document.body.appendChild(a);
      a.click();
      a.remove();
    });
    document.getElementById('scene-validate').addEventListener('click', async () => {
      const r = await postJson('/api/validate', { command: state.command, scene: sceneYaml() });
      if (r.ok) { clearErrors(); document.getElementById('scene-error').textContent = 'scene is valid'; } else showError(r.error);
    });
    document.getElementById('scene-run').addEventListener('click', () => startRun(state.command, sceneYaml(), ''));
    document.getElementById('run-cancel').addEventListener('click', () => { if (state.current) postJson(`/api/runs/${state.current}/cancel`, {}); });
    await initMotion();
    initParametric();
    document.body.dataset.ready = '1';
  }

  window.kimpGui = { toYaml: toYaml, fromYaml: fromYaml, sceneYaml: sceneYaml, loadScene: loadScene, startRun: startRun };
  init().catch((e) => { document.getElementById('scene-error').textContent = String(e); });
})();
