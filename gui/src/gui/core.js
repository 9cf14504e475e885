// kimp gui, part 1 of 6: the namespace `kimpGui` shared by the GUI's files (gui/src/gui/, joined in
// this order into the page script gui.js at build time, gui/assets.cmake), the GUI's state, the
// server access, the tabs, and the scene's YAML (written here, read by js-yaml). Results are drawn
// by the page script kimp.js (gui/src/kimp/).
'use strict';

const kimpGui = {};

(function () {
  // `restoring`: the session is not saved until the previous one has been restored (start.js).
  const state = {
    command: 'lumped', schema: null, schemas: {}, extra: {}, saved: {}, current: null, info: {}, restoring: true,
  };

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
    // Drawn by later files of the namespace, looked up when the tab is shown.
    if (name === 'runs') kimpGui.refreshRuns();
    if (name === 'motion') kimpGui.showMotion();
    if (kimpGui.saveSession) kimpGui.saveSession();
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

  Object.assign(kimpGui, {
    state, getJson, postJson, showTab, toYaml, fromYaml, unknownKeys, unknownPart, mergeInto,
  });
})();
