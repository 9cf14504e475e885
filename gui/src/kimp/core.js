// kimp results page, part 1 of 7: the namespace `kimp` shared by the page files (gui/src/kimp/,
// concatenated in this order into the page script kimp.js at build time, gui/assets.cmake), the
// page's state (charts, animations), small DOM and number helpers, kimp's unit symbols, and the
// access to a results file's series. The page is shared by `kimp report` (data inlined) and
// `kimp gui` (data fetched from the server).
'use strict';

const kimp = {};

(function () {
  const COLORS = [
    '#1f77b4',
    '#d62728',
    '#2ca02c',
    '#ff7f0e',
    '#9467bd',
    '#8c564b',
    '#e377c2',
    '#7f7f7f',
    '#bcbd22',
    '#17becf',
  ];
  /** What the page shows: its charts (for the time cursor) and its animations, if any. */
  const view = { charts: [], animation: null, femAnimation: null };

  // ---- display units: the reader's choice (kept in the browser), values stay SI in the data ----
  const DISPLAY_UNITS = {
    acceleration: { 'm/s²': 1, g: 1 / 9.80665 },
    force: { MN: 1e-6, kN: 1e-3 },
    length: { cm: 100, mm: 1000 },
    stiffness: { 'kN/mm': 1e-6, 'MN/m': 1e-6 },
  };
  const units = { acceleration: 'm/s²', force: 'MN', length: 'cm', stiffness: 'kN/mm' };
  try {
    const saved = JSON.parse(localStorage.getItem('kimp-units') || '{}');
    for (const [k, v] of Object.entries(saved)) if (DISPLAY_UNITS[k] && DISPLAY_UNITS[k][v]) units[k] = v;
  } catch {
    // No storage (a report opened from disk in some browsers): the defaults.
  }

  /** [factor from SI, unit text] of the chosen display unit of a quantity kind. */
  function displayUnit(kind) {
    return [DISPLAY_UNITS[kind][units[kind]], units[kind]];
  }

  function setDisplayUnit(kind, unit) {
    if (!DISPLAY_UNITS[kind] || DISPLAY_UNITS[kind][unit] === undefined) throw new Error(`unknown unit ${unit}`);
    units[kind] = unit;
    try {
      localStorage.setItem('kimp-units', JSON.stringify(units));
    } catch {
      // Not kept: the choice holds for this page.
    }
  }

  // ---- small helpers -------------------------------------------------------------------------
  function el(tag, attrs, children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === 'text') e.textContent = v;
      else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
      else e.setAttribute(k, v);
    }
    for (const c of children || []) if (c) e.appendChild(c);
    return e;
  }

  const INTEGER_INCRS = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000];

  function tickLabels(u, splits) {
    return splits.map((v) => fmt(v, 6));
  }

  function fmt(x, digits) {
    if (x === null || x === undefined || Number.isNaN(x)) return '';
    if (typeof x !== 'number') return String(x);
    if (!Number.isFinite(x)) return x > 0 ? '∞' : '−∞';
    return Number(x.toPrecision(digits || 4)).toString();
  }

  function download(name, text, type) {
    const url = URL.createObjectURL(new Blob([text], { type: type }));
    const a = el('a', { href: url, download: name });
    document.body.appendChild(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 1000);
  }

  function slug(text) {
    return (
      String(text)
        .replace(/[^A-Za-z0-9_.-]+/g, '_')
        .replace(/^_+|_+$/g, '') || 'chart'
    );
  }

  function niceTicks(min, max, count) {
    if (!(max > min)) return [min];
    const step0 = (max - min) / count;
    const mag = Math.pow(10, Math.floor(Math.log10(step0)));
    const norm = step0 / mag;
    const step = (norm < 1.5 ? 1 : norm < 3 ? 2 : norm < 7 ? 5 : 10) * mag;
    const ticks = [];
    for (let v = Math.ceil(min / step) * step; v <= max + step * 1e-9; v += step) {
      ticks.push(Math.abs(v) < step * 1e-9 ? 0 : v);
    }
    return ticks;
  }

  function parseCsv(text) {
    const rows = [];
    let row = [];
    let field = '';
    let quoted = false;
    for (let i = 0; i < text.length; ++i) {
      const c = text[i];
      if (quoted) {
        if (c === '"' && text[i + 1] === '"') {
          field += '"';
          ++i;
        } else if (c === '"') quoted = false;
        else field += c;
      } else if (c === '"') quoted = true;
      else if (c === ',') {
        row.push(field);
        field = '';
      } else if (c === '\n' || c === '\r') {
        if (c === '\r' && text[i + 1] === '\n') ++i;
        row.push(field);
        field = '';
        if (row.length > 1 || row[0] !== '') rows.push(row);
        row = [];
      } else field += c;
    }
    if (field !== '' || row.length) {
      row.push(field);
      rows.push(row);
    }
    return rows;
  }

  // ---- quantities: "5000 ms" -> 5 s, with kimp's own unit symbols (io/units.cc) ------------------
  const G = 9.80665;
  const UNITS = {
    m: [1, [0, 1, 0]],
    cm: [1e-2, [0, 1, 0]],
    mm: [1e-3, [0, 1, 0]],
    km: [1e3, [0, 1, 0]],
    s: [1, [0, 0, 1]],
    ms: [1e-3, [0, 0, 1]],
    kg: [1, [1, 0, 0]],
    t: [1e3, [1, 0, 0]],
    N: [1, [1, 1, -2]],
    kN: [1e3, [1, 1, -2]],
    MN: [1e6, [1, 1, -2]],
    Pa: [1, [1, -1, -2]],
    kPa: [1e3, [1, -1, -2]],
    MPa: [1e6, [1, -1, -2]],
    GPa: [1e9, [1, -1, -2]],
    g: [G, [0, 1, -2]],
    '%': [1e-2, [0, 0, 0]],
    1: [1, [0, 0, 0]],
  };

  /** A unit text ("kN/mm^1.5", "m/s^2") as [factor to SI, dimension exponents [kg, m, s]]. */
  function parseUnit(text) {
    const unit = String(text || '').trim();
    let factor = 1;
    const dim = [0, 0, 0];
    if (!unit) return [factor, dim];
    const parts = unit.split(/\s*([*/])\s*/);
    let sign = 1;
    for (let i = 0; i < parts.length; i += 2) {
      const m = /^([^\s^]+)\s*(?:\^\s*(-?\d+(?:\.\d+)?))?$/.exec(parts[i]);
      if (!m || !UNITS[m[1]]) {
        throw new Error(`unknown unit '${parts[i]}' in '${unit}' (known: ${Object.keys(UNITS).join(', ')})`);
      }
      const e = sign * (m[2] === undefined ? 1 : Number(m[2]));
      factor *= Math.pow(UNITS[m[1]][0], e);
      UNITS[m[1]][1].forEach((d, k) => {
        dim[k] += e * d;
      });
      sign = parts[i + 1] === '/' ? -1 : 1;
    }
    return [factor, dim];
  }

  /**
   * A scene quantity in SI, checked against the unit its key declares (the schema's unit):
   * "5000 ms" for a key in s gives 5; "0.5" for a key in s is refused as the CLI refuses it.
   */
  function parseQuantity(text, expectedUnit) {
    const t = String(text).trim();
    const m = /^([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*)$/.exec(t);
    if (!m) throw new Error(`'${t}' does not start with a number (expected a number with a unit, like '15 cm')`);
    const [factor, dim] = parseUnit(m[2]);
    const [, want] = parseUnit(expectedUnit);
    const same = dim.every((d, k) => Math.abs(d - want[k]) < 1e-9);
    if (!m[2] && want.some((d) => d !== 0))
      throw new Error(`'${t}' has no unit: expected a unit like '${expectedUnit}'`);
    if (!same) throw new Error(`'${t}' has the wrong dimension: expected units like '${expectedUnit}'`);
    return Number(m[1]) * factor;
  }

  // ---- results file access -------------------------------------------------------------------
  function column(values, j) {
    return values.map((row) => (Array.isArray(row) ? row[j] : row));
  }

  /** Time-series groups of a results file: {path, time: [], series: [{name, values, units}]}. */
  function seriesGroups(h5) {
    const byGroup = {};
    for (const [path, d] of Object.entries(h5.datasets)) {
      if (!Array.isArray(d.data) || d.shape.length < 1 || d.shape[0] < 3) continue;
      const cut = path.lastIndexOf('/');
      const g = path.slice(0, cut);
      (byGroup[g] = byGroup[g] || {})[path.slice(cut + 1)] = d;
    }
    const groups = [];
    for (const [g, members] of Object.entries(byGroup)) {
      if (g.endsWith('/frames')) continue; // the deformed-mesh frames: drawn by femSection
      let time = members.time;
      if (!time && members.value) {
        // Series sampled together share one time dataset, stored once (a hard link elsewhere).
        const parent = g.slice(0, g.lastIndexOf('/'));
        for (const [g2, m2] of Object.entries(byGroup)) {
          if (g2.startsWith(parent + '/') && m2.time && m2.time.data.length === members.value.data.length) {
            time = m2.time;
            break;
          }
        }
      }
      if (!time) continue;
      const series = [];
      for (const [name, d] of Object.entries(members)) {
        if (name === 'time' || name === 'step' || d.data.length !== time.data.length) continue;
        series.push({ name: name, values: d.data, units: d.units, width: d.shape[1] || 1 });
      }
      if (series.length) groups.push({ path: g, time: time.data, series: series });
    }
    return groups;
  }

  /** Column name of a CSV export: "name_unit" as in kimp's own tables (m/s² -> m_per_s2). */
  function csvName(name, unit) {
    const u = String(unit || '')
      .replace(/²/g, '2')
      .replace(/³/g, '3')
      .replace(/\^/g, '')
      .replace(/·/g, '_')
      .replace(/\//g, '_per_')
      .replace(/%/g, 'percent')
      .replace(/\s+/g, '_');
    const n = String(name)
      .replace(/[^A-Za-z0-9_.-]+/g, '_')
      .replace(/^_+|_+$/g, '');
    return u && u !== '-' && u !== '1' ? `${n}_${u}` : n;
  }

  /** "displacement (cm)" -> ["displacement", "cm"]; no unit -> [label, ""]. */
  function splitUnit(label) {
    const m = /^(.*?)\s*\(([^()]*)\)\s*$/.exec(String(label || ''));
    return m ? [m[1], m[2]] : [String(label || ''), ''];
  }

  function escapeXml(s) {
    return String(s).replace(/[<>&"]/g, (ch) => ({ '<': '&lt;', '>': '&gt;', '&': '&amp;', '"': '&quot;' })[ch]);
  }

  Object.assign(kimp, {
    view, COLORS, el, DISPLAY_UNITS, units, displayUnit, setDisplayUnit,
    INTEGER_INCRS, tickLabels, fmt, download, slug, niceTicks, parseCsv,
    parseQuantity, column, seriesGroups, csvName, splitUnit, escapeXml,
  });
})();
