// kimp results page: interactive charts (uPlot), tables and the building animation of one result
// directory, shared by `kimp report` (data inlined) and `kimp gui` (data fetched from the server).
// Chart export (SVG, PDF, CSV) is drawn here from the series data, not from uPlot's canvas.
'use strict';

const kimp = (function () {
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
  const charts = [];
  let animation = null;
  let femAnimation = null;

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

  // ---- vector export: one list of primitives, written as SVG or PDF --------------------------
  // A figure is {width, height, items: [{kind: 'line'|'path'|'rect'|'text'|'circle', ...}]}.
  function chartFigure(c) {
    const u = c.plot;
    const W = 720;
    const shownSeries = [];
    for (let s = 1; s < u.series.length; ++s) if (u.series[s].show) shownSeries.push(s);
    // Legend rows under the title, wrapped at the figure's width.
    const legend = [];
    let lx = 80;
    let row = 0;
    for (const s of shownSeries) {
      const w = 30 + 6.2 * String(u.series[s].label).length;
      if (lx + w > W - 10 && lx > 80) {
        lx = 80;
        ++row;
      }
      legend.push({ s: s, x: lx, row: row });
      lx += w;
    }
    const m = { left: 80, right: 20, top: 44 + 15 * row, bottom: 56 };
    const H = 400 + 15 * row;
    const pw = W - m.left - m.right;
    const ph = H - m.top - m.bottom;
    const xmin = u.scales.x.min;
    const xmax = u.scales.x.max;
    const ys = u.scales.y || u.scales[Object.keys(u.scales).find((k) => k !== 'x')];
    const ymin = ys.min;
    const ymax = ys.max;
    const X = (v) => m.left + ((v - xmin) / (xmax - xmin || 1)) * pw;
    const Y = (v) => m.top + ph - ((v - ymin) / (ymax - ymin || 1)) * ph;
    const items = [];
    items.push({ kind: 'rect', x: m.left, y: m.top, w: pw, h: ph, stroke: '#000', width: 1 });
    for (const t of niceTicks(xmin, xmax, 8).filter((v) => !c.integerX || Number.isInteger(v))) {
      items.push({ kind: 'line', x1: X(t), y1: m.top, x2: X(t), y2: m.top + ph, stroke: '#ddd', width: 0.5 });
      items.push({ kind: 'text', x: X(t), y: m.top + ph + 16, text: fmt(t, 6), anchor: 'middle', size: 11 });
    }
    for (const t of niceTicks(ymin, ymax, 6)) {
      items.push({ kind: 'line', x1: m.left, y1: Y(t), x2: m.left + pw, y2: Y(t), stroke: '#ddd', width: 0.5 });
      items.push({ kind: 'text', x: m.left - 6, y: Y(t) + 4, text: fmt(t, 6), anchor: 'end', size: 11 });
    }
    items.push({ kind: 'text', x: m.left + pw / 2, y: H - 14, text: c.xlabel, anchor: 'middle', size: 12 });
    items.push({ kind: 'text', x: 16, y: m.top + ph / 2, text: c.ylabel, anchor: 'middle', size: 12, rotate: -90 });
    items.push({ kind: 'text', x: m.left, y: 18, text: c.title, anchor: 'start', size: 14 });
    const data = u.data;
    for (const { s, x: legendX, row: r } of legend) {
      const stroke = u.series[s].stroke();
      const marker = c.markers[s - 1];
      // A null is a gap (a new piece of path); undefined is an alignment artefact (joined over).
      const pieces = [[]];
      for (let i = 0; i < data[0].length; ++i) {
        const x = data[0][i];
        const y = data[s][i];
        if (y === null) {
          if (pieces[pieces.length - 1].length) pieces.push([]);
          continue;
        }
        if (x < xmin || x > xmax || y === undefined || !Number.isFinite(y)) continue;
        pieces[pieces.length - 1].push([X(x), Y(Math.min(Math.max(y, ymin), ymax))]);
      }
      for (const pts of pieces) {
        if (c.scatter || marker) {
          // Loops (force against displacement): the samples as dots, not joined in x order.
          for (const p of pts) items.push({ kind: 'circle', x: p[0], y: p[1], r: marker ? 4 : 1.5, fill: stroke });
        } else if (pts.length) {
          items.push({ kind: 'path', points: pts, stroke: stroke, width: 1.2, dots: c.points, dash: c.dashes[s - 1] });
        }
      }
      const ly = 34 + 15 * r;
      if (marker) items.push({ kind: 'circle', x: legendX + 9, y: ly - 4, r: 4, fill: stroke });
      else
        items.push({ kind: 'line', x1: legendX, y1: ly - 4, x2: legendX + 18, y2: ly - 4, stroke: stroke, width: 2 });
      items.push({ kind: 'text', x: legendX + 22, y: ly, text: String(u.series[s].label), anchor: 'start', size: 11 });
    }
    return { width: W, height: H, items: items };
  }

  function escapeXml(s) {
    return String(s).replace(/[<>&"]/g, (ch) => ({ '<': '&lt;', '>': '&gt;', '&': '&amp;', '"': '&quot;' })[ch]);
  }

  function figureSvg(f) {
    const out = [
      `<svg xmlns="http://www.w3.org/2000/svg" width="${f.width}" height="${f.height}" ` +
        `viewBox="0 0 ${f.width} ${f.height}" font-family="Helvetica, Arial, sans-serif">`,
      `<rect width="${f.width}" height="${f.height}" fill="#fff"/>`,
    ];
    const n = (v) => (Math.round(v * 100) / 100).toString();
    for (const it of f.items) {
      if (it.kind === 'rect') {
        out.push(
          `<rect x="${n(it.x)}" y="${n(it.y)}" width="${n(it.w)}" height="${n(it.h)}" ` +
            `fill="${it.fill || 'none'}" stroke="${it.stroke || 'none'}" stroke-width="${it.width || 1}"/>`,
        );
      } else if (it.kind === 'line') {
        out.push(
          `<line x1="${n(it.x1)}" y1="${n(it.y1)}" x2="${n(it.x2)}" y2="${n(it.y2)}" ` +
            `stroke="${it.stroke}" stroke-width="${it.width}"/>`,
        );
      } else if (it.kind === 'path' && it.points.length) {
        const d = it.points.map((p, i) => (i ? 'L' : 'M') + n(p[0]) + ' ' + n(p[1])).join('');
        const dash = it.dash ? ` stroke-dasharray="${it.dash.join(' ')}"` : '';
        out.push(`<path d="${d}" fill="none" stroke="${it.stroke}" stroke-width="${it.width}"${dash}/>`);
        if (it.dots) {
          for (const p of it.points) out.push(`<circle cx="${n(p[0])}" cy="${n(p[1])}" r="2.5" fill="${it.stroke}"/>`);
        }
      } else if (it.kind === 'circle') {
        out.push(
          `<circle cx="${n(it.x)}" cy="${n(it.y)}" r="${n(it.r)}" fill="${it.fill}" ` +
            `fill-opacity="${it.opacity === undefined ? 1 : it.opacity}"/>`,
        );
      } else if (it.kind === 'text') {
        const rot = it.rotate ? ` transform="rotate(${it.rotate} ${n(it.x)} ${n(it.y)})"` : '';
        out.push(
          `<text x="${n(it.x)}" y="${n(it.y)}" font-size="${it.size}" text-anchor="${it.anchor}"${rot}>` +
            `${escapeXml(it.text)}</text>`,
        );
      }
    }
    out.push('</svg>');
    return out.join('\n');
  }

  // A minimal PDF 1.4 writer: one page, lines and Helvetica text, in points (1 px = 0.75 pt).
  function figurePdf(f) {
    const k = 0.75;
    const W = f.width * k;
    const H = f.height * k;
    const px = (x) => (x * k).toFixed(2);
    const py = (y) => (H - y * k).toFixed(2);
    const rgb = (hex) => {
      const h = (hex || '#000').replace('#', '');
      const v = h.length === 3 ? h.split('').map((c) => c + c) : [h.slice(0, 2), h.slice(2, 4), h.slice(4, 6)];
      return v.map((x) => (parseInt(x, 16) / 255).toFixed(3)).join(' ');
    };
    const text = (s) =>
      String(s)
        .replace(/[^\x20-\x7e]/g, '?')
        .replace(/([\\()])/g, '\\$1');
    const ops = ['1 J 1 j'];
    for (const it of f.items) {
      if (it.kind === 'rect') {
        ops.push(
          `${rgb(it.stroke)} RG ${(it.width || 1) * k} w ${px(it.x)} ${py(it.y + it.h)} ${px(it.w)} ${px(it.h)} re S`,
        );
      } else if (it.kind === 'line') {
        ops.push(`${rgb(it.stroke)} RG ${it.width * k} w ${px(it.x1)} ${py(it.y1)} m ${px(it.x2)} ${py(it.y2)} l S`);
      } else if (it.kind === 'path' && it.points.length) {
        const p = it.points;
        const dash = it.dash ? `[${it.dash.map((v) => (v * k).toFixed(1)).join(' ')}] 0 d` : '[] 0 d';
        ops.push(`${dash} ${rgb(it.stroke)} RG ${it.width * k} w ${px(p[0][0])} ${py(p[0][1])} m`);
        for (let i = 1; i < p.length; ++i) ops.push(`${px(p[i][0])} ${py(p[i][1])} l`);
        ops.push('S [] 0 d');
      } else if (it.kind === 'circle') {
        const r = it.r * k;
        const cx = it.x * k;
        const cy = H - it.y * k;
        const c = 0.5523 * r;
        // Four Bezier quarters: control points at 0.5523 r along the tangents.
        const p = (x, y) => `${x.toFixed(2)} ${y.toFixed(2)}`;
        ops.push(
          `${rgb(it.fill)} rg ${p(cx + r, cy)} m ` +
            `${p(cx + r, cy + c)} ${p(cx + c, cy + r)} ${p(cx, cy + r)} c ` +
            `${p(cx - c, cy + r)} ${p(cx - r, cy + c)} ${p(cx - r, cy)} c ` +
            `${p(cx - r, cy - c)} ${p(cx - c, cy - r)} ${p(cx, cy - r)} c ` +
            `${p(cx + c, cy - r)} ${p(cx + r, cy - c)} ${p(cx + r, cy)} c f`,
        );
      } else if (it.kind === 'text') {
        const size = it.size * k;
        const width = 0.5 * size * String(it.text).length;
        const dx = it.anchor === 'middle' ? -width / 2 : it.anchor === 'end' ? -width : 0;
        if (it.rotate) {
          const at = `${px(it.x)} ${(H - it.y * k + dx).toFixed(2)}`;
          ops.push(`BT 0 0 0 rg /F1 ${size} Tf 0 1 -1 0 ${at} Tm (${text(it.text)}) Tj ET`);
        } else {
          ops.push(`BT 0 0 0 rg /F1 ${size} Tf ${(it.x * k + dx).toFixed(2)} ${py(it.y)} Td (${text(it.text)}) Tj ET`);
        }
      }
    }
    const content = ops.join('\n');
    const objects = [
      '<< /Type /Catalog /Pages 2 0 R >>',
      '<< /Type /Pages /Kids [3 0 R] /Count 1 >>',
      `<< /Type /Page /Parent 2 0 R /MediaBox [0 0 ${W.toFixed(2)} ${H.toFixed(2)}] ` +
        '/Resources << /Font << /F1 4 0 R >> >> /Contents 5 0 R >>',
      '<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica >>',
      `<< /Length ${content.length} >>\nstream\n${content}\nendstream`,
    ];
    let pdf = '%PDF-1.4\n';
    const offsets = [];
    objects.forEach((o, i) => {
      offsets.push(pdf.length);
      pdf += `${i + 1} 0 obj\n${o}\nendobj\n`;
    });
    const xref = pdf.length;
    pdf += `xref\n0 ${objects.length + 1}\n0000000000 65535 f \n`;
    for (const o of offsets) pdf += String(o).padStart(10, '0') + ' 00000 n \n';
    pdf += `trailer\n<< /Size ${objects.length + 1} /Root 1 0 R >>\nstartxref\n${xref}\n%%EOF\n`;
    return pdf;
  }

  /** The shown series as CSV; the header names each column as name_unit (time_s, ..._cm). */
  function chartCsv(c) {
    const u = c.plot;
    const shown = u.series.map((s, i) => i).filter((i) => i === 0 || u.series[i].show);
    const [xName, xUnit] = splitUnit(c.xlabel);
    const [yName, yUnit] = splitUnit(c.ylabel);
    const head = shown.map((i) => {
      if (i === 0) return csvName(xName, xUnit);
      const [label, labelUnit] = splitUnit(u.series[i].label);
      if (c.units[i - 1] || labelUnit) return csvName(label, c.units[i - 1] || labelUnit);
      return csvName(yName && yName !== label ? `${label} ${yName}` : label, yUnit);
    });
    const lines = [head.map((h) => '"' + String(h).replace(/"/g, '""') + '"').join(',')];
    for (let r = 0; r < u.data[0].length; ++r) {
      lines.push(shown.map((i) => (u.data[i][r] === null || u.data[i][r] === undefined ? '' : u.data[i][r])).join(','));
    }
    return lines.join('\n') + '\n';
  }

  // ---- charts ----------------------------------------------------------------------------------
  function wheelZoom() {
    return {
      hooks: {
        ready: (u) => {
          u.over.addEventListener(
            'wheel',
            (e) => {
              e.preventDefault();
              const x = u.posToVal(e.offsetX, 'x');
              const f = e.deltaY < 0 ? 0.8 : 1.25;
              const min = x - (x - u.scales.x.min) * f;
              const max = x + (u.scales.x.max - x) * f;
              u.setScale('x', { min: min, max: max });
            },
            { passive: false },
          );
          // Shift-drag pans along x.
          u.over.addEventListener(
            'mousedown',
            (e) => {
              if (!e.shiftKey) return;
              e.stopPropagation();
              const x0 = e.clientX;
              const { min, max } = u.scales.x;
              const per = ((max - min) / u.bbox.width) * devicePixelRatio;
              const move = (ev) =>
                u.setScale('x', { min: min - (ev.clientX - x0) * per, max: max - (ev.clientX - x0) * per });
              const up = () => {
                document.removeEventListener('mousemove', move);
                document.removeEventListener('mouseup', up);
              };
              document.addEventListener('mousemove', move);
              document.addEventListener('mouseup', up);
            },
            true,
          );
        },
      },
    };
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

  /**
   * A chart card: spec = {title, xlabel, ylabel, x: [], series: [{label, y: [], x?: [], unit?,
   * dash?, marker?}], time: bool, points: bool, scatter: bool, integerX: bool, height}.
   * A series with its own x (another run, another sampling) is aligned with uPlot.join; a marker
   * series is a few labelled points (a peak). time charts show the animation's time cursor and
   * scrub it on click. The chart follows the width of its card (drawn while hidden, it widens
   * when shown).
   */
  function chart(parent, spec) {
    const card = el('div', { class: 'chart card' });
    const bar = el('div', { class: 'chart-bar' }, [el('span', { class: 'chart-title', text: spec.title })]);
    card.appendChild(bar);
    const host = el('div', { class: 'chart-host' });
    card.appendChild(host);
    parent.appendChild(card);
    const widthOf = () => Math.max(320, Math.min(card.clientWidth || parent.clientWidth || 900, 1400) - 12);
    const ownX = spec.series.some((s) => s.x);
    const opts = {
      width: widthOf(),
      height: spec.height || 300,
      scales: { x: { time: false } },
      cursor: { sync: { key: spec.time ? 'kimp-time' : 'kimp-' + Math.random() } },
      // Tick labels to 6 significant digits: uPlot's default rounds to the tick step's decimals,
      // which repeats labels on narrow ranges (0.001, 0.001, 0.002 for steps of 0.5 ms).
      axes: [
        { label: spec.xlabel, values: tickLabels, space: 50, incrs: spec.integerX ? INTEGER_INCRS : undefined },
        { label: spec.ylabel, size: 70, values: tickLabels, space: 25 },
      ],
      series: [{ label: spec.xlabel }].concat(
        spec.series.map((s, i) => {
          const color = s.color || COLORS[i % COLORS.length];
          if (s.marker) {
            return {
              label: s.label,
              stroke: color,
              width: 0,
              paths: () => null,
              points: { show: true, size: 9, fill: color, stroke: '#000', width: 1 },
            };
          }
          return {
            label: s.label,
            stroke: color,
            width: 1.2,
            dash: s.dash,
            spanGaps: ownX,
            points: spec.scatter ? { show: true, size: 4, fill: color } : { show: !!spec.points },
            // A loop's samples are not ordered in x: dots only (uPlot joins in x order otherwise).
            paths: spec.scatter ? () => null : undefined,
          };
        }),
      ),
      plugins: [wheelZoom()],
    };
    const data = ownX
      ? uPlot.join(spec.series.map((s) => [s.x || spec.x, s.y]))
      : [spec.x].concat(spec.series.map((s) => s.y));
    const plot = new uPlot(opts, data, host);
    const c = {
      plot: plot,
      title: spec.title,
      xlabel: spec.xlabel,
      ylabel: spec.ylabel,
      points: spec.points,
      scatter: !!spec.scatter,
      card: card,
      time: spec.time,
      integerX: !!spec.integerX,
      units: spec.series.map((s) => s.unit),
      markers: spec.series.map((s) => !!s.marker),
      dashes: spec.series.map((s) => s.dash),
    };
    if (typeof ResizeObserver !== 'undefined') {
      let last = opts.width;
      new ResizeObserver(() => {
        if (!card.clientWidth) return;
        const w = widthOf();
        if (Math.abs(w - last) > 2) {
          last = w;
          plot.setSize({ width: w, height: opts.height });
        }
      }).observe(card);
    }
    const name = slug(spec.title);
    const exporters = [
      ['svg', 'SVG', 'download the chart as SVG (vector)', () => figureSvg(chartFigure(c)), 'image/svg+xml'],
      ['pdf', 'PDF', 'download the chart as PDF (vector)', () => figurePdf(chartFigure(c)), 'application/pdf'],
      ['csv', 'CSV', 'download the shown series as CSV', () => chartCsv(c), 'text/csv'],
    ];
    for (const [ext, text, title, make, type] of exporters) {
      bar.appendChild(
        el('button', {
          class: 'export-' + ext,
          text: text,
          title: title,
          onclick: () => download(name + '.' + ext, make(), type),
        }),
      );
    }
    if (spec.time) {
      c.cursor = el('div', { class: 'time-cursor' });
      plot.over.appendChild(c.cursor);
      // A click moves the animation to that time (the building's, or the FEM mesh's frame).
      plot.over.addEventListener('click', (e) => {
        const t = plot.posToVal(e.offsetX, 'x');
        if (spec.seek) spec.seek(t);
        else if (animation) animation.seek(t);
      });
    }
    charts.push(c);
    return c;
  }

  function setTimeCursor(t) {
    for (const c of charts) {
      if (!c.cursor || !c.plot.scales.x) continue;
      const x = c.plot.valToPos(t, 'x');
      c.cursor.style.display = x >= 0 && x <= c.plot.over.clientWidth ? 'block' : 'none';
      c.cursor.style.left = x + 'px';
    }
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

  // ---- sections --------------------------------------------------------------------------------
  function section(parent, title, open) {
    const d = el('details', { class: 'section' });
    if (open !== false) d.setAttribute('open', '');
    d.appendChild(el('summary', { text: title }));
    const body = el('div', { class: 'section-body' });
    d.appendChild(body);
    parent.appendChild(d);
    return body;
  }

  function table(parent, header, rows, cls) {
    const t = el('table', { class: cls || 'data' });
    t.appendChild(
      el('thead', {}, [
        el(
          'tr',
          {},
          header.map((h) => el('th', { text: h })),
        ),
      ]),
    );
    const tb = el('tbody');
    for (const r of rows)
      tb.appendChild(
        el(
          'tr',
          {},
          r.map((v) => (v instanceof Node ? el('td', {}, [v]) : el('td', { text: v }))),
        ),
      );
    t.appendChild(tb);
    parent.appendChild(el('div', { class: 'table-wrap' }, [t]));
    return t;
  }

  /** A table cell as a number: "0.5", "1e-3", or a quantity "10 cm" (its number, in its unit). */
  function cellNumber(v) {
    return /^\s*-?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?(\s*[A-Za-z%/^.0-9*]+)?\s*$/.test(v) ? parseFloat(v) : NaN;
  }

  /** The unit a column's cells carry ("10 cm" -> "cm"), or "" for plain numbers. */
  function cellUnit(rows, j) {
    for (const r of rows) {
      const m = /^\s*-?[\d.]+(?:[eE][-+]?\d+)?\s*([A-Za-z%][A-Za-z%/^.0-9*]*)\s*$/.exec(r[j] || '');
      if (m) return m[1];
    }
    return '';
  }

  /** The column as numbers in one unit (a sweep may write "10 cm" and "0.2 m" in one column). */
  function columnNumbers(rows, j) {
    const unit = cellUnit(rows, j);
    return rows.map((r) => {
      if (r[j] === '' || r[j] === undefined) return null;
      if (!unit) return cellNumber(r[j]);
      try {
        return parseQuantity(r[j], unit) / parseQuantity(`1 ${unit}`, unit);
      } catch {
        return cellNumber(r[j]);
      }
    });
  }

  /**
   * A CSV file as a table and a chart of chosen columns. preset = {x, groups: [[y columns], ...]
   * (one chart per group: columns of one unit), group: [columns] (one series per distinct value
   * of these), chart: false}.
   */
  function csvSection(parent, name, text, preset) {
    const rows = parseCsv(text);
    if (rows.length < 2) return null;
    const head = rows[0];
    const body = rows.slice(1);
    const sec = section(parent, name, rows.length <= 60);
    // 4 significant figures on screen for real numbers (integers such as counts stay whole; the
    // CSV export and the file keep full precision).
    const shown = (v) => (/^\s*-?(\d+\.\d*|\.\d+|\d+(\.\d*)?[eE][-+]?\d+)\s*$/.test(v) ? fmt(parseFloat(v), 4) : v);
    table(
      sec,
      head,
      body.slice(0, 200).map((r) => r.map(shown)),
    );
    if (body.length > 200) sec.appendChild(el('p', { text: `first 200 of ${body.length} rows` }));
    if (preset && preset.chart === false) return sec;
    const numeric = head.map((h, j) => body.some((r) => r[j] !== '' && Number.isFinite(cellNumber(r[j]))));
    const cols = head.map((h, j) => j).filter((j) => numeric[j]);
    if (cols.length < 2) return sec;
    const label = (j) => (cellUnit(body, j) ? `${head[j]} (${cellUnit(body, j)})` : head[j]);
    const xs = el(
      'select',
      { class: 'csv-x' },
      cols.map((j) => el('option', { value: j, text: label(j) })),
    );
    const ys = el(
      'select',
      { class: 'csv-y', multiple: '', size: Math.min(6, cols.length) },
      cols.map((j) => el('option', { value: j, text: label(j) })),
    );
    // Group by: a column of few distinct values (a second swept parameter, a case, a velocity).
    const distinct = (j) => new Set(body.map((r) => r[j])).size;
    const groupable = head
      .map((h, j) => j)
      .filter((j) => distinct(j) > 1 && distinct(j) <= 12 && distinct(j) < body.length);
    const groupOptions = [el('option', { value: '', text: 'nothing' })];
    if (preset && preset.group && preset.group.length > 1) {
      groupOptions.push(
        el('option', { value: preset.group.join(','), text: preset.group.map((j) => head[j]).join(' + ') }),
      );
    }
    for (const j of groupable) groupOptions.push(el('option', { value: String(j), text: head[j] }));
    const group = el('select', { class: 'csv-group' }, groupOptions);
    const host = el('div');
    const draw = () => {
      host.innerHTML = '';
      const xj = Number(xs.value);
      const chosen = Array.from(ys.selectedOptions).map((o) => Number(o.value));
      if (!chosen.length) return;
      const gj =
        group.value === ''
          ? []
          : group.value
              .split(',')
              .map(Number)
              .filter((j) => j !== xj);
      const keyOf = (r) => gj.map((j) => `${head[j]} = ${r[j] || '-'}`).join(', ');
      const keys = Array.from(new Set(body.map(keyOf)));
      const xValues = columnNumbers(body, xj);
      const integerX = xValues.every((v) => v === null || Number.isInteger(v));
      const chartGroups =
        preset && preset.groups && chosen.length > 1
          ? preset.groups
              .map((g) => g.map((n) => head.indexOf(n)).filter((j) => chosen.includes(j)))
              .filter((g) => g.length)
          : [chosen];
      for (const yjs of chartGroups) {
        const series = [];
        for (const key of keys) {
          const idx = body
            .map((r, i) => i)
            .filter((i) => keyOf(body[i]) === key && xValues[i] !== null)
            .sort((a, b) => xValues[a] - xValues[b]);
          for (const yj of yjs) {
            const yv = columnNumbers(body, yj);
            series.push({
              label: [yjs.length > 1 || !key ? head[yj] : '', key].filter((t) => t).join(', '),
              x: idx.map((i) => xValues[i]),
              y: idx.map((i) => yv[i]),
            });
          }
        }
        chart(host, {
          title:
            `${name}: ${yjs.map((j) => head[j]).join(', ')} over ${head[xj]}` +
            (gj.length ? ', by ' + gj.map((j) => head[j]).join(' + ') : ''),
          xlabel: label(xj),
          ylabel: yjs.length === 1 ? label(yjs[0]) : '',
          points: true,
          integerX: integerX,
          x: series[0].x,
          series: series,
        });
      }
    };
    const pickX =
      preset && preset.x !== undefined ? (typeof preset.x === 'number' ? preset.x : head.indexOf(preset.x)) : -1;
    if (pickX >= 0) xs.value = String(pickX);
    else {
      // A column of values with units is the swept parameter; the first peak is the response.
      const withUnit = cols.find((j) => body.every((r) => r[j] === '' || /[A-Za-z%]\s*$/.test(r[j])));
      xs.value = String(withUnit === undefined ? cols[0] : withUnit);
    }
    const wanted = preset && preset.groups ? preset.groups.flat() : preset && preset.y ? preset.y : null;
    if (wanted) for (const o of ys.options) o.selected = wanted.includes(head[Number(o.value)]);
    if (!Array.from(ys.selectedOptions).length) {
      const x = Number(xs.value);
      const peak = cols.find((j) => j !== x && /peak/.test(head[j]));
      const y = peak === undefined ? cols.find((j) => j !== x) : peak;
      for (const o of ys.options) o.selected = Number(o.value) === y;
    }
    if (preset && preset.group) group.value = preset.group.join(',');
    xs.addEventListener('change', draw);
    ys.addEventListener('change', draw);
    group.addEventListener('change', draw);
    sec.appendChild(
      el('div', { class: 'controls' }, [
        el('label', { text: 'x ' }, [xs]),
        el('label', { text: ' y ' }, [ys]),
        el('label', { text: ' one series per ' }, [group]),
      ]),
    );
    sec.appendChild(host);
    draw();
    return sec;
  }

  function seriesSection(parent, file, h5) {
    const groups = seriesGroups(h5);
    if (!groups.length) return;
    const body = section(parent, `All histories in ${file} (${groups.length})`, false);
    const pick = el(
      'select',
      { class: 'series-pick' },
      groups.map((g, i) => el('option', { value: i, text: g.path })),
    );
    const host = el('div');
    const draw = () => {
      host.innerHTML = '';
      const g = groups[Number(pick.value)];
      const series = [];
      for (const s of g.series) {
        for (let j = 0; j < s.width; ++j) {
          series.push({
            label: s.width > 1 ? `${s.name}[${j}] (${s.units})` : `${s.name} (${s.units})`,
            y: column(s.values, j),
          });
        }
      }
      chart(host, { title: g.path, xlabel: 'time (s)', ylabel: '', x: g.time, series: series, time: false });
    };
    pick.addEventListener('change', draw);
    body.appendChild(el('div', { class: 'controls' }, [el('label', { text: 'history ' }, [pick])]));
    body.appendChild(host);
    draw();
  }

  // ---- lumped runs -----------------------------------------------------------------------------
  const SCALE = { m: [100, 'cm'], 'm/s^2': [1, 'm/s²'], N: [1e-6, 'MN'] };

  /**
   * The cases of a lumped run: [{summary, label, run, resolved, nMain, isolated, history,
   * pulses}]. `run` names the run when several runs are overlaid (the legend shows run: case).
   */
  function lumpedCases(data, run) {
    const h5 = data.h5['lumped.h5'];
    const resolved = JSON.parse(h5.datasets['/input/resolved'].data);
    const isolated = resolved.building.kind === 'isolated';
    const nMain = resolved.building.n_storeys + (isolated ? 1 : 0);
    const groups = seriesGroups(h5);
    const cases = (data.summary && data.summary.cases ? data.summary.cases : []).map((c) => {
      const hist = {};
      const pulses = {};
      const prefix = `/lumped/${c.name}/history/`;
      for (const g of groups) {
        if (g.path.startsWith(prefix)) {
          hist[g.path.slice(prefix.length)] = { time: g.time, values: g.series[0].values, units: g.series[0].units };
        }
      }
      for (const k of c.contacts || []) {
        const base = `/lumped/${c.name}/contacts/${k.name}`;
        const v = h5.datasets[`${base}/force_full_rate/value`];
        const t = h5.datasets[`${base}/force_full_rate/time`];
        const at = h5.datasets[`${base}/impact_time`];
        if (v && t && Array.isArray(v.data) && v.data.length) {
          pulses[k.name] = {
            time: t.data,
            force: v.data,
            stride: v.stride || 1,
            rows: v.shape[0],
            impacts: at && Array.isArray(at.data) ? at.data : [],
          };
        }
      }
      return {
        summary: c,
        label: run ? `${run}: ${c.name}` : c.name,
        run: run,
        resolved: resolved,
        nMain: nMain,
        isolated: isolated,
        history: hist,
        pulses: pulses,
      };
    });
    return cases.filter((c) => c.history.displacement);
  }

  function levelNames(n, isolated) {
    const names = [];
    for (let i = 0; i < n; ++i) names.push(isolated ? (i === 0 ? 'isolation level' : `floor ${i}`) : `floor ${i + 1}`);
    return names;
  }

  /** True when every case samples its histories at the same times (one x for all series). */
  function sameTimes(cases, key) {
    const t0 = cases[0].history[key].time;
    return cases.every((c) => {
      const t = c.history[key].time;
      return t === t0 || (t.length === t0.length && t[0] === t0[0] && t[t.length - 1] === t0[t0.length - 1]);
    });
  }

  /** The full-rate force samples of one contact split into pulses at the force-free gaps. */
  function splitPulses(p) {
    const t = p.time;
    const steps = [];
    for (let i = 1; i < t.length; ++i) steps.push(t[i] - t[i - 1]);
    const typical = steps.length ? steps.slice().sort((a, b) => a - b)[Math.floor(steps.length / 2)] : 0;
    const out = [];
    let cur = null;
    for (let i = 0; i < t.length; ++i) {
      if (!cur || t[i] - t[i - 1] > 10 * typical) {
        cur = { start: t[i], time: [], force: [] };
        out.push(cur);
      }
      cur.time.push(t[i]);
      cur.force.push(p.force[i]);
    }
    return out;
  }

  function lumpedSection(parent, data, others) {
    const cases = lumpedCases(data, others && others.length ? data.title : null);
    for (const o of others || []) if (o.h5 && o.h5['lumped.h5']) cases.push(...lumpedCases(o, o.title));
    if (!cases.length) return;
    const first = cases[0];
    const { isolated } = first;

    // Peaks table: the numbers of summary.json, in engineering units.
    const body = section(parent, 'Peaks (summary.json)');
    const firstLevel = isolated ? 'peak isolation displacement (cm)' : 'peak floor 1 displacement (cm)';
    const contactNames = Array.from(new Set(cases.flatMap((c) => c.summary.contacts.map((k) => k.name))));
    const header = [
      'case',
      'status',
      firstLevel,
      'peak top displacement (cm)',
      'max interstorey drift (cm)',
      'peak absolute acceleration (m/s²)',
      'impacts',
    ].concat(contactNames.map((n) => `peak force ${n} (MN)`));
    const rows = cases.map((c) => {
      const s = c.summary;
      const cell = (v, scale, key) =>
        el('span', {
          class: 'peak',
          'data-key': key,
          'data-si': String(v),
          'data-scale': String(scale),
          text: fmt(v * scale, 6),
        });
      const top = c.nMain - 1;
      return [
        c.label,
        s.status,
        cell(s.peaks.displacement[0], 100, `${s.name}.displacement.0`),
        cell(s.peaks.displacement[top], 100, `${s.name}.displacement.${top}`),
        cell(s.max_interstorey_drift, 100, `${s.name}.max_interstorey_drift`),
        cell(Math.max(...s.peaks.absolute_acceleration.slice(0, c.nMain)), 1, `${s.name}.absolute_acceleration.max`),
        String(s.n_impacts),
      ].concat(
        contactNames.map((n) => {
          const k = s.contacts.find((x) => x.name === n);
          return k ? cell(k.peak_force, 1e-6, `${s.name}.${n}.peak_force`) : '';
        }),
      );
    });
    table(body, header, rows, 'data peaks');

    // Case chooser shared by the charts below (overlay of several cases, or runs, on one chart).
    const chooser = el('div', { class: 'controls case-chooser' }, [el('span', { text: 'cases: ' })]);
    const firstOfRun = new Set();
    cases.forEach((c, i) => {
      const box = el('input', { type: 'checkbox', value: i, class: 'case-box' });
      if (!firstOfRun.has(c.run)) {
        box.checked = true;
        firstOfRun.add(c.run);
      }
      chooser.appendChild(el('label', {}, [box, document.createTextNode(c.label + ' ')]));
    });
    const hbody = section(parent, 'Histories');
    hbody.appendChild(chooser);
    const hostH = el('div');
    hbody.appendChild(hostH);
    const pbody = section(parent, 'Peak profiles over the floors');
    const hostP = el('div');
    pbody.appendChild(hostP);
    const fbody = section(parent, 'Impact force pulses at full rate');
    const hostF = el('div');
    fbody.appendChild(hostF);
    const lbody = section(parent, 'Force-indentation loops', false);
    const hostL = el('div');
    lbody.appendChild(hostL);
    const hostI = el('div');
    if (isolated) section(parent, 'Isolator hysteresis loop').appendChild(hostI);

    const nLevels = first.history.displacement.values[0].length;
    const quantities = [
      ['displacement', 'displacement', 'm', levelNames(nLevels, isolated)],
      ['interstorey_drift', 'interstorey drift', 'm', null],
      ['absolute_acceleration', 'absolute acceleration', 'm/s^2', null],
      ['contact_force', 'impact force', 'N', first.summary.contacts.map((k) => k.name)],
      ['isolator_force', 'isolator force', 'N', ['isolator']],
    ];
    const picks = {};
    const draw = () => {
      const chosen = Array.from(chooser.querySelectorAll('input:checked')).map((b) => cases[Number(b.value)]);
      for (const host of [hostH, hostP, hostF, hostL, hostI]) host.innerHTML = '';
      charts.length = 0;
      if (!chosen.length) return;
      for (const [key, label, unit, names0] of quantities) {
        const having = chosen.filter((c) => c.history[key]);
        if (!having.length) continue;
        const h0 = having[0].history[key];
        const width = Array.isArray(h0.values[0]) ? h0.values[0].length : 1;
        const names =
          names0 ||
          Array.from({ length: width }, (_, j) =>
            key === 'interstorey_drift' ? `storey ${j + 1}` : levelNames(width, isolated)[j],
          );
        if (!picks[key]) {
          picks[key] = el(
            'select',
            { class: 'component-pick', 'data-quantity': key },
            names.slice(0, width).map((n, j) => el('option', { value: j, text: n })),
          );
          if (key === 'displacement' || key === 'absolute_acceleration') picks[key].value = '0';
          picks[key].addEventListener('change', draw);
        }
        const j = Number(picks[key].value);
        const [scale, shown] = SCALE[unit] || [1, unit];
        // Contacts are matched by name across runs (the column order may differ).
        const column0 = (c) => (key === 'contact_force' ? c.summary.contacts.findIndex((k) => k.name === names[j]) : j);
        const own = !sameTimes(having, key);
        hostH.appendChild(el('div', { class: 'controls' }, [el('label', { text: label + ' of ' }, [picks[key]])]));
        chart(hostH, {
          title: `${label}: ${names[j]}`,
          xlabel: 'time (s)',
          ylabel: `${label} (${shown})`,
          time: true,
          x: h0.time,
          series: having
            .filter((c) => column0(c) >= 0)
            .map((c) => ({
              label: c.label,
              x: own ? c.history[key].time : undefined,
              y: column(c.history[key].values, column0(c)).map((v) => v * scale),
            })),
        });
      }
      // Peak profiles: level on x (integers), peak on y, one series per case.
      const profiles = [
        ['displacement', 'peak displacement', 'm'],
        ['interstorey_drift', 'peak interstorey drift', 'm'],
        ['absolute_acceleration', 'peak absolute acceleration', 'm/s^2'],
      ];
      for (const [key, label, unit] of profiles) {
        const [scale, shown] = SCALE[unit];
        const levels = (c) => {
          const n = key === 'interstorey_drift' ? c.nMain - (c.isolated ? 1 : 0) : c.nMain;
          const from = key === 'interstorey_drift' && c.isolated ? 1 : 0;
          return Array.from({ length: n }, (_, i) => i + from);
        };
        const own = chosen.some((c) => c.nMain !== chosen[0].nMain);
        chart(hostP, {
          title: `${label} over the floors`,
          xlabel: isolated ? 'level (0 = isolation)' : 'floor',
          ylabel: `${label} (${shown})`,
          points: true,
          integerX: true,
          x: levels(chosen[0]),
          series: chosen.map((c) => ({
            label: c.label,
            x: own ? levels(c) : undefined,
            y: c.summary.peaks[key].slice(0, levels(c).length).map((v) => v * scale),
          })),
        });
      }
      drawPulses(hostF, chosen);
      drawLoops(hostL, chosen);
      // Isolator hysteresis: its force on the base against the isolation level's displacement.
      const withIsolator = chosen.filter((c) => c.isolated && c.history.isolator_force);
      if (withIsolator.length) {
        const series = withIsolator.map((c) => {
          const f = column(c.history.isolator_force.values, 0);
          const u = column(c.history.displacement.values, 0);
          return { label: c.label, pairs: u.map((d, i) => [d * 100, f[i] * 1e-6]) };
        });
        const kind = withIsolator[0].summary.isolator ? ` (${withIsolator[0].summary.isolator.kind})` : '';
        scatterChart(hostI, `isolator hysteresis${kind}`, 'isolation displacement (cm)', 'isolator force (MN)', series);
      }
      if (animation) animation.setCase(chosen[0]);
    };
    chooser.addEventListener('change', draw);
    const abody = section(parent, 'Animation');
    animation = makeAnimation(abody, first);
    draw();
  }

  /** Samples as dots (a loop is not ordered in x): series = [{label, pairs: [[x, y]]}]. */
  function scatterChart(host, title, xlabel, ylabel, series) {
    const allX = Array.from(new Set(series.flatMap((s) => s.pairs.map((p) => p[0])))).sort((a, b) => a - b);
    const index = new Map(allX.map((x, i) => [x, i]));
    return chart(host, {
      title: title,
      xlabel: xlabel,
      ylabel: ylabel,
      scatter: true,
      x: allX,
      series: series.map((s) => {
        const y = new Array(allX.length).fill(null);
        for (const p of s.pairs) y[index.get(p[0])] = p[1];
        return { label: s.label, y: y };
      }),
    });
  }

  /**
   * Every impact's force at every time step (contacts/<name>/force_full_rate of lumped.h5) against
   * the time since the impact began: the pulse shape of each impact of each chosen case.
   */
  function drawPulses(host, chosen) {
    const MAX_IMPACTS = 8;
    const names = Array.from(new Set(chosen.flatMap((c) => Object.keys(c.pulses))));
    if (!names.length) {
      host.appendChild(el('p', { class: 'muted', text: 'No impact in the chosen cases.' }));
      return;
    }
    const notes = [
      "Each impact's contact force at every time step (lumped.h5 contacts/<name>/force_full_rate), " +
        'against the time since the impact began.',
    ];
    for (const name of names) {
      const series = [];
      for (const c of chosen) {
        const p = c.pulses[name];
        if (!p) continue;
        const pieces = splitPulses(p);
        if (pieces.length > MAX_IMPACTS)
          notes.push(`${c.label} ${name}: the first ${MAX_IMPACTS} of ${pieces.length} impacts drawn.`);
        if (p.stride > 1)
          notes.push(`${c.label} ${name}: every ${p.stride}th of ${p.rows} samples (report size limit).`);
        pieces.slice(0, MAX_IMPACTS).forEach((piece, k) =>
          series.push({
            label: `${c.label} #${k + 1} (t = ${fmt(piece.start, 4)} s)`,
            x: piece.time.map((t) => (t - piece.start) * 1e3),
            y: piece.force.map((f) => f * 1e-6),
          }),
        );
      }
      if (!series.length) continue;
      // One x per impact: aligned by uPlot.join (points of other impacts are gaps, joined over).
      const order = series.map((s) => {
        const idx = s.x.map((_, i) => i).sort((a, b) => s.x[a] - s.x[b]);
        return { label: s.label, x: idx.map((i) => s.x[i]), y: idx.map((i) => s.y[i]) };
      });
      chart(host, {
        title: `impact force pulses at full rate: ${name}`,
        xlabel: 'time since the impact began (ms)',
        ylabel: 'impact force (MN)',
        x: order[0].x,
        series: order,
      });
    }
    host.insertBefore(el('p', { class: 'muted pulse-note', text: notes.join(' ') }), host.firstChild);
  }

  /**
   * Force against indentation from the histories. The walls are fixed, so the indentation is the
   * isolation level's displacement beyond the gap; a neighbour contact uses both floors. The
   * histories are sampled every integration.output_interval: a loop needs many samples per impact,
   * and lumped.h5 keeps the indentation only at those samples (the force alone at full rate).
   */
  function drawLoops(host, chosen) {
    const MIN_SAMPLES = 20;
    const names = Array.from(new Set(chosen.flatMap((c) => c.summary.contacts.map((k) => k.name))));
    const notes = [];
    for (const name of names) {
      const series = [];
      for (const c of chosen) {
        if (!c.history.contact_force) continue;
        const k = c.summary.contacts.findIndex((x) => x.name === name);
        const ind = k < 0 ? null : indentation(name, c.history.displacement.values, c.resolved, c.nMain);
        if (!ind) continue;
        const f = column(c.history.contact_force.values, k);
        const pairs = ind.map((d, i) => [d * 1000, f[i] * 1e-6]).filter((p, i) => f[i] > 0 || (i > 0 && f[i - 1] > 0));
        const nImpacts = c.summary.contacts[k].impacts ? c.summary.contacts[k].impacts.length : 0;
        if (!nImpacts) continue;
        const perImpact = pairs.length / nImpacts;
        const dt = c.history.contact_force.time[1] - c.history.contact_force.time[0];
        if (perImpact < MIN_SAMPLES) {
          notes.push(
            `${c.label} ${name}: ${fmt(perImpact, 2)} history samples per impact (every ${fmt(dt, 3)} s), ` +
              `too few for a loop.`,
          );
          continue;
        }
        series.push({ label: c.label, pairs: pairs });
      }
      if (series.length)
        scatterChart(host, `force-indentation: ${name}`, 'indentation (mm)', 'impact force (MN)', series);
    }
    if (notes.length) {
      host.insertBefore(
        el('p', {
          class: 'muted loop-note',
          text:
            notes.join(' ') +
            ' lumped.h5 keeps the contact force ' +
            'at every step but the indentation only at the history samples: set integration.output_interval to a ' +
            'fraction of a contact duration (e.g. "1e-4 s") for loops; the pulses above are at full rate.',
        }),
        host.firstChild,
      );
    }
  }

  function indentation(name, u, r, nMain) {
    const m = /^(left|right)_(wall|neighbour_floor(\d+))$/.exec(name);
    if (!m) return null;
    const side = m[1];
    if (m[2] === 'wall') {
      const gap = r.walls[side].gap;
      return u.map((row) => (side === 'right' ? row[0] - gap : -row[0] - gap));
    }
    const floor = Number(m[3]);
    const nb = r.neighbours[side];
    const offset = nMain + (side === 'right' && r.neighbours.left.present ? r.neighbours.left.n_storeys : 0);
    const main = floor - 1 + (r.building.kind === 'isolated' ? 1 : 0);
    return u.map((row) =>
      side === 'right'
        ? row[main] - row[offset + floor - 1] - nb.separation
        : row[offset + floor - 1] - row[main] - nb.separation,
    );
  }

  // ---- animation -------------------------------------------------------------------------------
  // ---- animations: the controls, SVG and playback shared by the building and the FEM mesh ------
  const SVG_NS = 'http://www.w3.org/2000/svg';

  /** An animation's SVG element, width × height user units, of class `cls`. */
  function animationSvg(width, height, cls) {
    const svg = document.createElementNS(SVG_NS, 'svg');
    svg.setAttribute('viewBox', `0 0 ${width} ${height}`);
    svg.setAttribute('class', cls);
    svg.setAttribute('xmlns', SVG_NS);
    return svg;
  }

  /** The drawn frame of `svg` as a standalone SVG file (white background). */
  function frameSvgText(svg, width, height) {
    return (
      `<svg xmlns="${SVG_NS}" viewBox="0 0 ${width} ${height}" width="${width}" height="${height}" ` +
      'font-family="Helvetica, Arial, sans-serif">' +
      `<rect width="${width}" height="${height}" fill="#fff"/>${svg.innerHTML}</svg>`
    );
  }

  /**
   * The controls of an animation, of classes `${prefix}-play`, ...: Play, Restart, speed (`o.speeds`,
   * 1× chosen), exaggeration (1 to `o.maxExaggeration`, starting at `o.exaggeration`), Frame SVG, in
   * that order in `items`, and the scrub bar (0 to `o.scrubMax`).
   */
  function animationControls(prefix, o) {
    const speed = el(
      'select',
      { class: `${prefix}-speed` },
      o.speeds.map((s) => el('option', { value: s, text: s + '×' })),
    );
    speed.value = '1';
    const c = {
      play: el('button', { class: `${prefix}-play`, text: 'Play' }),
      restart: el('button', { class: `${prefix}-restart`, text: 'Restart' }),
      speed: speed,
      exag: el('input', {
        type: 'number',
        min: 1,
        max: o.maxExaggeration,
        step: 1,
        value: o.exaggeration,
        class: `${prefix}-exaggeration`,
      }),
      exportFrame: el('button', { class: `${prefix}-export`, text: 'Frame SVG' }),
      scrub: el('input', { type: 'range', min: 0, max: o.scrubMax, value: 0, class: `${prefix}-scrub` }),
    };
    c.items = [
      c.play,
      c.restart,
      el('label', { text: ' speed ' }, [c.speed]),
      el('label', { text: ' exaggeration ×' }, [c.exag]),
      c.exportFrame,
    ];
    return c;
  }

  /**
   * The playback of an animation whose `state.playing` it keeps: Play/Pause on `controls.play`,
   * Restart (`h.seek(0)`, which draws, then play), and a frame loop that calls `h.step(ms)` with
   * the wall time since the last frame, stops when `h.atEnd()` and draws with `h.draw()`.
   * `h.start()` runs before playing (rewind at the end). Returns the animation's API so far:
   * { state, play, pause, seek }.
   */
  function playback(state, controls, h) {
    let last = null;
    function tick(now) {
      if (!state.playing) {
        last = null;
        return;
      }
      if (last !== null) h.step(now - last);
      last = now;
      if (h.atEnd()) {
        state.playing = false;
        controls.play.textContent = 'Play';
      }
      h.draw();
      if (state.playing) requestAnimationFrame(tick);
    }
    const player = {
      state: state,
      play: () => {
        if (state.playing) return;
        h.start();
        state.playing = true;
        controls.play.textContent = 'Pause';
        requestAnimationFrame(tick);
      },
      pause: () => {
        state.playing = false;
        controls.play.textContent = 'Play';
      },
      seek: h.seek,
    };
    controls.play.addEventListener('click', () => (state.playing ? player.pause() : player.play()));
    controls.restart.addEventListener('click', () => {
      h.seek(0);
      player.play();
    });
    return player;
  }

  function makeAnimation(parent, firstCase) {
    const W = 900;
    const H = 420;
    const svg = animationSvg(W, H, 'animation');
    const state = { t: 0, playing: false, speed: 1, exaggeration: 10, frame: 0, kase: null };
    const timeLabel = el('span', { id: 'anim-time', class: 'anim-time', text: 't = 0 s' });
    const controls = animationControls('anim', {
      speeds: [0.1, 0.25, 0.5, 1, 2, 5],
      exaggeration: 10,
      maxExaggeration: 200,
      scrubMax: 1000,
    });
    const { speed, exag, exportFrame, scrub } = controls;
    parent.appendChild(el('div', { class: 'controls' }, [...controls.items, timeLabel]));
    parent.appendChild(scrub);
    parent.appendChild(svg);

    const times = () => state.kase.history.displacement.time;
    const tEnd = () => times()[times().length - 1];
    const frameAt = (t) => {
      const ts = times();
      let lo = 0;
      let hi = ts.length - 1;
      while (hi - lo > 1) {
        const mid = (lo + hi) >> 1;
        if (ts[mid] <= t) lo = mid;
        else hi = mid;
      }
      return ts[hi] <= t ? hi : lo;
    };
    const groundY = H - 40;
    const widthMain = 160;
    // The drawn frame's own time (the history sample), to the digits its sampling needs.
    const frameTime = () => times()[state.frame];
    const timeText = (t) => {
      const ts = times();
      const dt = ts.length > 1 ? ts[1] - ts[0] : 0.01;
      return t.toFixed(Math.min(6, Math.max(2, Math.ceil(-Math.log10(dt) - 1e-9))));
    };

    function draw() {
      if (!state.kase) return;
      // The case's own model (cases of overlaid runs may differ).
      const { resolved: r, nMain, isolated } = state.kase;
      const storeyH = 300 / (Math.max(nMain, 4) + 0.5);
      // Drawing scale: a storey is 3 m; displacements and gaps are drawn `exaggeration` times larger.
      const pxPerM = storeyH / 3;
      const i = frameAt(state.t);
      state.frame = i;
      const u = state.kase.history.displacement.values[i];
      const e = state.exaggeration * pxPerM;
      const cx = W / 2;
      const parts = [];
      const line = (x1, y1, x2, y2, color, w) =>
        parts.push(
          `<line x1="${x1.toFixed(1)}" y1="${y1.toFixed(1)}" x2="${x2.toFixed(1)}" y2="${y2.toFixed(1)}" ` +
            `stroke="${color}" stroke-width="${w}"/>`,
        );
      line(0, groundY, W, groundY, '#654', 3);
      // Main building: level 0 is the isolation level (on the isolators) or floor 1.
      const levelY = (k) => groundY - (isolated ? 18 + k * storeyH : (k + 1) * storeyH);
      const xs = u.slice(0, nMain).map((v) => cx + v * e);
      if (isolated) {
        for (const dx of [-widthMain / 2 + 15, widthMain / 2 - 15])
          line(cx + dx, groundY, xs[0] + dx, levelY(0), '#888', 5);
      }
      for (const side of [-1, 1]) {
        let px = cx + (side * widthMain) / 2;
        let py = groundY;
        for (let k = isolated ? 0 : -1; k < nMain; ++k) {
          const x = (k < 0 ? cx : xs[k]) + (side * widthMain) / 2;
          const y = k < 0 ? groundY : levelY(k);
          if (k >= (isolated ? 1 : 0)) line(px, py, x, y, '#345', 3);
          px = x;
          py = y;
        }
      }
      for (let k = 0; k < nMain; ++k)
        line(xs[k] - widthMain / 2, levelY(k), xs[k] + widthMain / 2, levelY(k), '#123', 6);
      // Moat walls at the gap on either side of the isolation level.
      for (const side of ['left', 'right']) {
        const w = r.walls && r.walls[side];
        if (!w || !w.present) continue;
        const s = side === 'right' ? 1 : -1;
        const x = cx + s * (widthMain / 2 + w.gap * e);
        parts.push(
          `<rect x="${(s > 0 ? x : x - 14).toFixed(1)}" y="${(levelY(0) - 16).toFixed(1)}" width="14" ` +
            `height="${(groundY - levelY(0) + 16).toFixed(1)}" fill="#999"/>`,
        );
      }
      // Neighbours: fixed-base shear buildings across their separation.
      let offset = nMain;
      for (const side of ['left', 'right']) {
        const nb = r.neighbours && r.neighbours[side];
        if (!nb || !nb.present) continue;
        const s = side === 'right' ? 1 : -1;
        const face = cx + s * (widthMain / 2 + nb.separation * e);
        const wN = 120;
        const base = face + (s * wN) / 2;
        const nx = u.slice(offset, offset + nb.n_storeys).map((v) => base + v * e);
        const ny = (k) => levelY(k + (isolated ? 1 : 0));
        for (const side2 of [-1, 1]) {
          let px = base + (side2 * wN) / 2;
          let py = groundY;
          for (let k = 0; k < nb.n_storeys; ++k) {
            line(px, py, nx[k] + (side2 * wN) / 2, ny(k), '#575', 3);
            px = nx[k] + (side2 * wN) / 2;
            py = ny(k);
          }
        }
        for (let k = 0; k < nb.n_storeys; ++k) line(nx[k] - wN / 2, ny(k), nx[k] + wN / 2, ny(k), '#353', 6);
        offset += nb.n_storeys;
      }
      // Impacts flash with their force.
      const cf = state.kase.history.contact_force;
      if (cf) {
        const f = Array.isArray(cf.values[i]) ? cf.values[i] : [cf.values[i]];
        state.kase.summary.contacts.forEach((c, k) => {
          if (!(f[k] > 0)) return;
          const m = /^(left|right)_(wall|neighbour_floor(\d+))$/.exec(c.name);
          if (!m) return;
          const s = m[1] === 'right' ? 1 : -1;
          const level = m[2] === 'wall' ? 0 : Number(m[3]) - (isolated ? 0 : 1);
          const x = xs[level] + (s * widthMain) / 2;
          const y = levelY(level);
          const rr = 6 + 24 * Math.sqrt(f[k] / Math.max(c.peak_force, 1));
          parts.push(
            `<circle cx="${x.toFixed(1)}" cy="${y.toFixed(1)}" r="${rr.toFixed(1)}" fill="#e00" ` +
              'fill-opacity="0.6" class="impact"/>',
          );
          // The force beside its circle, outwards (levels are a storey apart: labels never meet),
          // on a white box over the walls and neighbours.
          const text = `${fmt(f[k] * 1e-6, 3)} MN`;
          const w = 7.4 * text.length + 6;
          const x0 = s > 0 ? x + rr + 2 : x - rr - 2 - w;
          parts.push(
            `<rect class="impact-label-box" x="${x0.toFixed(1)}" y="${(y - 9).toFixed(1)}" width="${w.toFixed(1)}" ` +
              'height="18" rx="3" fill="#fff" fill-opacity="0.9" stroke="#b00" stroke-width="0.5"/>',
          );
          parts.push(
            `<text class="impact-label" x="${(x0 + w / 2).toFixed(1)}" y="${(y + 4.5).toFixed(1)}" font-size="13" ` +
              `text-anchor="middle" fill="#b00">${text}</text>`,
          );
        });
      }
      const tFrame = frameTime();
      parts.push(
        `<text x="10" y="20" font-size="14">${escapeXml(state.kase.label)}: t = ${timeText(tFrame)} s, ` +
          `displacements ×${state.exaggeration}</text>`,
      );
      svg.innerHTML = parts.join('');
      timeLabel.textContent = `t = ${timeText(tFrame)} s`;
      scrub.value = String(Math.round((state.t / tEnd()) * 1000));
      setTimeCursor(state.t);
    }

    const api = playback(state, controls, {
      step: (ms) => {
        state.t = Math.min(state.t + (ms / 1000) * state.speed, tEnd());
      },
      atEnd: () => state.t >= tEnd(),
      start: () => {
        if (state.t >= tEnd()) state.t = 0;
      },
      seek: (t) => {
        state.t = Math.max(0, Math.min(t, tEnd()));
        draw();
      },
      draw: draw,
    });
    Object.assign(api, {
      setCase: (c) => {
        state.kase = c;
        state.t = Math.min(state.t, tEnd());
        draw();
      },
      frameSvg: () => frameSvgText(svg, W, H),
    });
    speed.addEventListener('change', () => {
      state.speed = Number(speed.value);
    });
    exag.addEventListener('change', () => {
      state.exaggeration = Math.max(1, Number(exag.value) || 1);
      draw();
    });
    scrub.addEventListener('input', () => api.seek((Number(scrub.value) / 1000) * tEnd()));
    exportFrame.addEventListener('click', () =>
      download(`frame_t${timeText(frameTime())}.svg`, api.frameSvg(), 'image/svg+xml'),
    );
    api.setCase(firstCase);
    return api;
  }

  // ---- FEM: the deformed mesh over the impact ------------------------------------------------
  /** Colour of v in [0, 1] on a perceptually ordered blue-green-yellow ramp (viridis stops). */
  function ramp(v) {
    const stops = [
      [68, 1, 84],
      [59, 82, 139],
      [33, 145, 140],
      [94, 201, 98],
      [253, 231, 37],
    ];
    const x = Math.max(0, Math.min(1, v)) * (stops.length - 1);
    const i = Math.min(stops.length - 2, Math.floor(x));
    const f = x - i;
    const c = stops[i].map((a, k) => Math.round(a + f * (stops[i + 1][k] - a)));
    return `rgb(${c[0]},${c[1]},${c[2]})`;
  }

  function femSection(parent, data) {
    const h5 = data.h5['fem.h5'];
    const d = h5.datasets;
    const names = Object.keys(d)
      .map((k) => /^\/fem\/([^/]+)\/frames\/time$/.exec(k))
      .filter((m) => m)
      .map((m) => m[1]);
    if (!names.length) return;
    const body = section(parent, 'Deformed mesh over the impact');
    const FIELDS = [
      ['von_mises_stress', 'von Mises stress', 1e-6, 'MPa'],
      ['mean_stress', 'mean stress', 1e-6, 'MPa'],
      ['damage', 'damage', 1, '-'],
      ['equivalent_plastic_strain', 'equivalent plastic strain', 1, '-'],
    ];
    const W = 900;
    const H = 440;
    const caseSel = el(
      'select',
      { class: 'fem-case' },
      names.map((n) => el('option', { value: n, text: n })),
    );
    const fieldSel = el('select', { class: 'fem-field' });
    const controls = animationControls('fem', {
      speeds: [0.25, 0.5, 1, 2, 4],
      exaggeration: 1,
      maxExaggeration: 100000,
      scrubMax: 0,
    });
    const { speed, exag, exportFrame, scrub } = controls;
    const label = el('span', { class: 'fem-time', text: '' });
    body.appendChild(
      el('div', { class: 'controls' }, [
        el('label', { text: 'case ' }, [caseSel]),
        el('label', { text: ' colour by ' }, [fieldSel]),
        ...controls.items,
        label,
      ]),
    );
    body.appendChild(scrub);
    const svg = animationSvg(W, H, 'fem-animation');
    body.appendChild(svg);
    const state = { frame: 0, playing: false, mesh: null };
    // The case's contact force beside the mesh: its time cursor follows the frame.
    const forceHost = el('div');
    body.appendChild(forceHost);
    const drawForce = (name) => {
      forceHost.innerHTML = '';
      const raw = d[`/fem/${name}/contact_force/value`];
      const time = d[`/fem/${name}/contact_force/time`];
      if (!raw || !time) return;
      const series = [{ label: 'raw', y: raw.data.map((v) => v * 1e-3) }];
      const smooth = d[`/fem/${name}/smoothed_contact_force/value`];
      if (smooth && smooth.data.length === raw.data.length)
        series.push({ label: 'smoothed', y: smooth.data.map((v) => v * 1e-3) });
      // A click on the force history moves the mesh to the frame at that time.
      chart(forceHost, {
        title: `${name}: contact force`,
        xlabel: 'time (s)',
        ylabel: 'force (kN/m)',
        time: true,
        x: time.data,
        series: series,
        seek: (t) => api.seekTime(t),
      });
    };

    function load(name) {
      const g = (k) => d[`/fem/${name}/frames/${k}`];
      const m = {
        name: name,
        time: g('time').data,
        vertices: g('vertices').data,
        cells: g('cells').data,
        displacement: g('displacement').data,
        fields: {},
      };
      for (const [key, text, scale, unit] of FIELDS) {
        if (!g(key)) continue;
        let lo = Infinity;
        let hi = -Infinity;
        for (const row of g(key).data)
          for (const v of row) {
            lo = Math.min(lo, v);
            hi = Math.max(hi, v);
          }
        m.fields[key] = { values: g(key).data, text: text, scale: scale, unit: unit, lo: lo, hi: hi };
      }
      // The contact pressure is per contact node, not per cell: drawn on the contact face only.
      const cv = g('contact_vertices');
      const cp = g('contact_pressure');
      if (cv && cp && cv.data.length > 1) {
        let hi = 0;
        for (const row of cp.data) for (const v of row) hi = Math.max(hi, v);
        const nodes = cv.data.map(Number);
        // The cell of each face between neighbouring contact nodes (two of its vertices).
        const faceCell = nodes.slice(1).map((b, k) => m.cells.findIndex((c) => c.includes(nodes[k]) && c.includes(b)));
        m.fields.contact_pressure = {
          values: cp.data,
          text: 'contact pressure',
          scale: hi >= 1e6 ? 1e-6 : 1e-3,
          unit: hi >= 1e6 ? 'MPa' : 'kPa',
          lo: 0,
          hi: hi,
          nodes: nodes,
          faceCell: faceCell,
          length: g('contact_length') ? g('contact_length').data : null,
        };
      }
      let x0 = Infinity;
      let x1 = -Infinity;
      let y0 = Infinity;
      let y1 = -Infinity;
      for (const [x, y] of m.vertices) {
        x0 = Math.min(x0, x);
        x1 = Math.max(x1, x);
        y0 = Math.min(y0, y);
        y1 = Math.max(y1, y);
      }
      m.box = [x0, x1, y0, y1];
      // Exaggeration that draws the largest displacement as 3 % of the model's size.
      let umax = 0;
      for (const row of m.displacement) for (const v of row) umax = Math.max(umax, Math.abs(v));
      m.autoExaggeration = umax > 0 ? Math.max(1, Math.round((0.03 * Math.max(x1 - x0, y1 - y0)) / umax)) : 1;
      return m;
    }

    function draw() {
      const m = state.mesh;
      const f = m.fields[fieldSel.value];
      const i = state.frame;
      const u = m.displacement[i];
      const e = Math.max(1, Number(exag.value) || 1);
      const [x0, x1, y0, y1] = m.box;
      const sc = Math.min((W - 140) / (x1 - x0), (H - 70) / (y1 - y0));
      const X = (x) => 20 + (x - x0) * sc;
      const Y = (y) => H - 20 - (y - y0) * sc;
      const parts = [];
      const span = f.hi - f.lo || 1;
      const at = (v) => [X(m.vertices[v][0] + e * u[2 * v]), Y(m.vertices[v][1] + e * u[2 * v + 1])];
      // Nodal field (contact pressure): the mesh neutral, the cells along the contact face in
      // the mean pressure of their face, and over them each node's tributary part of the face.
      const cellFill = new Map();
      if (f.nodes)
        f.faceCell.forEach((c, k) => {
          if (c >= 0) cellFill.set(c, ramp((0.5 * (f.values[i][k] + f.values[i][k + 1])) / span));
        });
      m.cells.forEach((c, k) => {
        const pts = c
          .map((v) =>
            at(v)
              .map((z) => z.toFixed(1))
              .join(','),
          )
          .join(' ');
        const fill = f.nodes ? cellFill.get(k) || '#d9d9d9' : ramp((f.values[i][k] - f.lo) / span);
        parts.push(`<polygon points="${pts}" fill="${fill}" stroke="#0003" stroke-width="0.3"/>`);
      });
      if (f.nodes) {
        const p = f.nodes.map(at);
        const mid = (a, b) => [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        f.nodes.forEach((v, k) => {
          const from = k > 0 ? mid(p[k - 1], p[k]) : p[k];
          const to = k + 1 < p.length ? mid(p[k], p[k + 1]) : p[k];
          const xy = [from, p[k], to].map((q) => q.map((z) => z.toFixed(1)).join(',')).join(' ');
          parts.push(
            `<polyline class="contact-face" points="${xy}" fill="none" ` +
              `stroke="${ramp(f.values[i][k] / span)}" stroke-width="7"/>`,
          );
        });
        // The face is short beside the model: its profile as bars, bottom to top (inset).
        const [ix, iy, iw, ih] = [W - 430, 44, 190, 150];
        const ys = f.nodes.map((v) => m.vertices[v][1]);
        const [ya, yb] = [Math.min(...ys), Math.max(...ys)];
        const bh = Math.max(2, Math.min(14, (0.8 * ih) / f.nodes.length));
        parts.push(
          `<g class="pressure-profile"><rect x="${ix - 8}" y="${iy - 26}" width="${iw + 16}" height="${ih + 52}" ` +
            'fill="#fff" fill-opacity="0.9" stroke="#0003"/>',
        );
        parts.push(`<text x="${ix}" y="${iy - 10}" font-size="11">pressure along the face (${f.unit})</text>`);
        f.nodes.forEach((v, k) => {
          const yc = iy + ih - bh / 2 - (yb > ya ? (ys[k] - ya) / (yb - ya) : 0.5) * (ih - bh);
          const w = Math.max(0, f.values[i][k] / span) * iw;
          parts.push(
            `<rect x="${ix}" y="${(yc - bh / 2).toFixed(1)}" width="${w.toFixed(1)}" height="${bh.toFixed(1)}" ` +
              `fill="${ramp(f.values[i][k] / span)}"/>`,
          );
        });
        parts.push(`<line x1="${ix}" y1="${iy}" x2="${ix}" y2="${iy + ih}" stroke="#000"/>`);
        parts.push(`<text x="${ix}" y="${iy + ih + 14}" font-size="10">0</text>`);
        parts.push(
          `<text x="${ix + iw}" y="${iy + ih + 14}" font-size="10" text-anchor="end">${fmt(f.hi * f.scale, 4)}</text>`,
        );
        parts.push(
          `<text x="${ix + iw / 2}" y="${iy + ih + 14}" font-size="10" text-anchor="middle">` +
            `y ${fmt(ya, 4)} to ${fmt(yb, 4)} m</text></g>`,
        );
      }
      // Colour bar: the field's range over all frames.
      const bx = W - 100;
      for (let j = 0; j < 50; ++j) {
        parts.push(
          `<rect x="${bx}" y="${(40 + (49 - j) * 6).toFixed(1)}" width="18" height="6.5" fill="${ramp(j / 49)}"/>`,
        );
      }
      parts.push(`<text x="${bx + 24}" y="46" font-size="12">${fmt(f.hi * f.scale, 4)}</text>`);
      parts.push(`<text x="${bx + 24}" y="340" font-size="12">${fmt(f.lo * f.scale, 4)}</text>`);
      parts.push(
        `<text x="${W - 8}" y="28" font-size="12" text-anchor="end">${escapeXml(`${f.text} (${f.unit})`)}</text>`,
      );
      const t = m.time[i];
      parts.push(
        `<text x="20" y="22" font-size="14">${escapeXml(m.name)}: t = ${fmt(t * 1e3, 4)} ms, ` +
          `displacements ×${e}</text>`,
      );
      svg.innerHTML = parts.join('');
      label.textContent = ` frame ${i + 1}/${m.time.length}, t = ${fmt(t * 1e3, 4)} ms`;
      scrub.value = String(i);
      setTimeCursor(t);
    }

    function setCase(name) {
      state.mesh = load(name);
      drawForce(name);
      const keep = fieldSel.value;
      fieldSel.innerHTML = '';
      for (const key of Object.keys(state.mesh.fields))
        fieldSel.appendChild(el('option', { value: key, text: state.mesh.fields[key].text }));
      if (state.mesh.fields[keep]) fieldSel.value = keep;
      exag.value = String(state.mesh.autoExaggeration);
      scrub.max = String(state.mesh.time.length - 1);
      state.frame = 0;
      draw();
    }

    let carry = 0;
    const atEnd = () => state.frame >= state.mesh.time.length - 1;
    const api = playback(state, controls, {
      step: (ms) => {
        // 10 frames per second at speed 1.
        carry += (ms / 100) * Number(speed.value);
        while (carry >= 1 && !atEnd()) {
          carry -= 1;
          state.frame += 1;
        }
      },
      atEnd: atEnd,
      start: () => {
        if (atEnd()) state.frame = 0;
        carry = 0;
      },
      seek: (i) => {
        state.frame = Math.max(0, Math.min(i, state.mesh.time.length - 1));
        draw();
      },
      draw: draw,
    });
    Object.assign(api, {
      /** The frame nearest to time t (s). */
      seekTime: (t) => {
        const ts = state.mesh.time;
        let best = 0;
        for (let k = 1; k < ts.length; ++k) if (Math.abs(ts[k] - t) < Math.abs(ts[best] - t)) best = k;
        api.seek(best);
      },
      time: () => state.mesh.time[state.frame],
      frameSvg: () => frameSvgText(svg, W, H),
    });
    caseSel.addEventListener('change', () => setCase(caseSel.value));
    fieldSel.addEventListener('change', draw);
    exag.addEventListener('change', draw);
    scrub.addEventListener('input', () => api.seek(Number(scrub.value)));
    exportFrame.addEventListener('click', () =>
      download(`${state.mesh.name}_frame${state.frame}.svg`, api.frameSvg(), 'image/svg+xml'),
    );
    setCase(names[0]);
    femAnimation = api;
  }

  // ---- study -----------------------------------------------------------------------------------
  function studySection(parent, data) {
    const h5 = data.h5['study.h5'];
    if (!h5) return;
    studyVelocitySection(parent, h5);
    const groups = seriesGroups(h5).filter((g) => g.path.startsWith('/fit/'));
    if (!groups.length) return;
    const body = section(parent, 'FEM force histories with the fitted laws');
    for (const g of groups) {
      chart(body, {
        title: `${g.path.slice(5)}: FEM and fitted force`,
        xlabel: 'time (s)',
        ylabel: 'force (kN/m)',
        x: g.time,
        series: g.series.map((s) => ({ label: s.name, y: s.values.map((v) => v * 1e-3) })),
      });
    }
  }

  // ---- fem: the summary of every case in engineering units, 4 significant figures -------------
  // Rows: [summary key, label, scale from the SI value]; a row shows when any case has the key.
  const femSummaryRows = [
    ['wall_height', 'wall height (m)', 1],
    ['impact_velocity', 'impact velocity (m/s)', 1],
    ['peak_force', 'peak contact force (kN/m)', 1e-3],
    ['contact_duration', 'contact duration (ms)', 1e3],
    ['impulse', 'impulse (N·s/m)', 1],
    ['apparent_cor', 'apparent COR', 1],
    ['stopped_on', 'run stopped on', null],
    ['max_penetration', 'largest penetration (mm)', 1e3],
    ['permanent_indentation', 'permanent indentation (mm)', 1e3],
    ['wall_residual_displacement', 'wall face at the end (mm)', 1e3],
    ['plastic_dissipation', 'plastic dissipation (J/m)', 1],
    ...['slab', 'wall', 'soil'].map((r) => [`plastic_dissipation_${r}`, `plastic dissipation in the ${r} (J/m)`, 1]),
    ['damage_dissipation', 'damage dissipation (J/m)', 1],
    ...['slab', 'wall'].map((r) => [`damage_dissipation_${r}`, `damage dissipation in the ${r} (J/m)`, 1]),
    ['contact_dissipation', 'contact dissipation (J/m)', 1],
    ['radiated_energy', 'radiated energy (J/m)', 1],
    ['energy_error', 'energy balance error (of E_0)', 1],
    ['n_dofs', 'DoFs', null],
    ['n_steps', 'steps', null],
    ['dt', 'time step (µs)', 1e6],
    ['dt_stable', 'stable limit (µs)', 1e6],
    ['wall_time', 'solver time (s)', 1],
  ];

  function femSummarySection(parent, summary) {
    const cases = (summary.cases || []).filter((c) => c && typeof c === 'object');
    if (!cases.length) return;
    const body = section(parent, 'FEM summary (summary.json)');
    const rows = [];
    for (const [key, label, scale] of femSummaryRows) {
      if (!cases.some((c) => c[key] !== undefined && c[key] !== null)) continue;
      rows.push(
        [label].concat(
          cases.map((c) => {
            const v = c[key];
            if (typeof v !== 'number' || scale === null) return v === undefined || v === null ? '' : String(v);
            return el('span', {
              class: 'fem-summary-value',
              'data-key': `${c.name}.${key}`,
              'data-si': String(v),
              text: fmt(v * scale, 4),
            });
          }),
        ),
      );
    }
    table(body, ['quantity'].concat(cases.map((c) => c.name)), rows, 'data fem-summary');
  }

  // k(H, v): k against the impact velocity, one series per wall height (and its linear k).
  function studyVelocitySection(parent, h5) {
    const d = h5.datasets || {};
    const column = (name) => (d[`/k_table_velocity/${name}`] || {}).data;
    const hs = column('wall_height');
    const vs = column('impact_velocity');
    if (!hs || !vs || new Set(vs).size < 2) return;
    const body = section(parent, 'Impact stiffness against impact velocity, k(H, v)');
    const xs = Array.from(new Set(vs)).sort((a, b) => a - b);
    const heights = Array.from(new Set(hs)).sort((a, b) => a - b);
    for (const [law, unit] of [
      ['kelvin_voigt', 'kN/mm/m'],
      ['jankowski', 'kN/mm^1.5/m'],
    ]) {
      const series = [];
      for (const [key, suffix] of [
        [law, ''],
        [`linear_${law}`, ', linear'],
      ]) {
        const k = column(key);
        if (!k) continue;
        for (const height of heights) {
          const y = xs.map((x) => {
            const i = hs.findIndex((h, j) => h === height && vs[j] === x);
            return i < 0 ? null : k[i];
          });
          if (y.some((v) => v !== null)) series.push({ label: `H = ${fmt(height, 3)} m${suffix}`, y: y });
        }
      }
      if (!series.length) continue;
      chart(body, {
        title: `${law.replace('_', '-')} k against impact velocity`,
        xlabel: 'impact velocity (m/s)',
        ylabel: `k (${unit})`,
        points: true,
        x: xs,
        series: series,
      });
    }
  }

  // ---- collide: the laws' COR tables overlaid ----------------------------------------------
  function collideSection(parent, data, others) {
    // Every law of every run (overlaid runs name theirs "run: law").
    const laws = [];
    const runs = [data].concat((others || []).filter((o) => o.h5 && o.h5['collide.h5']));
    for (const run of runs) {
      const d = run.h5['collide.h5'].datasets;
      for (const k of Object.keys(d)) {
        const m = /^\/collide\/([^/]+)\/cor_table\/nominal_cor$/.exec(k);
        if (m) laws.push({ label: runs.length > 1 ? `${run.title}: ${m[1]}` : m[1], d: d, law: m[1] });
      }
    }
    if (!laws.length) return;
    const body = section(parent, 'Two-body impacts: every law over the nominal COR');
    const column = (l, key) => l.d[`/collide/${l.law}/cor_table/${key}`];
    const quantities = [
      ['effective_cor', 'effective COR', 1, ''],
      ['peak_force', 'peak force', 1e-6, 'MN'],
      ['contact_duration', 'contact duration', 1e3, 'ms'],
      ['max_penetration', 'max penetration', 1e3, 'mm'],
    ];
    for (const [key, label, scale, unit] of quantities) {
      const having = laws.filter((l) => column(l, key));
      if (!having.length) continue;
      chart(body, {
        title: `${label} over the nominal COR`,
        xlabel: 'nominal COR',
        ylabel: unit ? `${label} (${unit})` : label,
        points: true,
        x: column(having[0], 'nominal_cor').data,
        series: having.map((l) => ({
          label: l.label,
          x: column(l, 'nominal_cor').data,
          y: column(l, key).data.map((v) => (v === null ? null : v * scale)),
        })),
      });
    }
  }

  // ---- sweeps: the swept values grouped by the other parameters, and the d_req / d_SRSS table --
  /** Parameter columns of sweep.csv: between "companion" (or "id") and "status". */
  function sweepParameters(head) {
    const from = head.indexOf('companion') >= 0 ? head.indexOf('companion') : head.indexOf('id');
    const to = head.indexOf('status');
    return from >= 0 && to > from ? head.slice(from + 1, to).map((h, k) => from + 1 + k) : [];
  }

  function sweepSection(parent, data) {
    const rows = parseCsv(data.csv['sweep.csv']);
    if (rows.length < 2) return;
    const head = rows[0];
    const body = rows.slice(1);
    const params = sweepParameters(head);
    // x: the first swept quantity with a unit (a gap), else the first numeric parameter; one
    // series per value of the other parameters (and of the companion runs).
    const numericParam = params.filter((j) => body.every((r) => r[j] === '' || Number.isFinite(cellNumber(r[j]))));
    const x = numericParam.find((j) => cellUnit(body, j)) ?? numericParam[0] ?? params[0];
    const group = params.filter((j) => j !== x);
    const comp = head.indexOf('companion');
    if (comp >= 0 && body.some((r) => r[comp] !== '')) group.push(comp);
    const metric = ['max_interstorey_drift_m', 'peak_displacement_dof0_m', 'n_impacts'].find((m) =>
      head.some((h) => h === m || h.endsWith('.' + m)),
    );
    const y = metric ? head.filter((h) => h === metric || h.endsWith('.' + metric)) : undefined;
    csvSection(parent, 'sweep.csv', data.csv['sweep.csv'], { x: x, group: group, y: y });
  }

  /**
   * dsrss_table.csv of a gap sweep: the gap the sweep needed to avoid every impact (d_req) beside
   * the SRSS estimate of the separation (d_SRSS), per value of the other swept parameters.
   */
  function dsrssSection(parent, data) {
    const rows = parseCsv(data.csv['dsrss_table.csv']);
    if (rows.length < 2) return;
    const head = rows[0];
    const body = rows.slice(1);
    const col = (n) => head.indexOf(n);
    const groupCols = head.slice(0, Math.max(0, col('clearance_offset_m'))).map((h, j) => j);
    const cm = (v) => (v === '' || v === undefined ? '' : fmt(parseFloat(v) * 100, 4));
    const sec = section(parent, 'Required gap d_req and the SRSS estimate d_SRSS (dsrss_table.csv)');
    sec.appendChild(
      el('p', {
        class: 'muted',
        text:
          'd_req: the smallest swept gap with no impact (not_reached: every ' +
          'swept gap had impacts); d_SRSS: the SRSS of the free (no-contact companion) peak displacements across the ' +
          'gap; Δd = d_req − d_SRSS.',
      }),
    );
    const header = groupCols
      .map((j) => head[j])
      .concat([
        'd_req (cm)',
        'd_req status',
        'd_SRSS (cm)',
        'governing contact',
        'Δd (cm)',
        'd_SRSS spread (cm)',
        'gaps swept (cm)',
        'cases (failed)',
      ]);
    table(
      sec,
      header,
      body.map((r) =>
        groupCols
          .map((j) => r[j])
          .concat([
            el('span', { class: 'd-req', 'data-si': r[col('d_req_m')], text: cm(r[col('d_req_m')]) }),
            r[col('d_req_status')],
            el('span', { class: 'd-srss', 'data-si': r[col('d_srss_m')], text: cm(r[col('d_srss_m')]) }),
            r[col('governing_contact')],
            cm(r[col('delta_d_m')]),
            cm(r[col('d_srss_spread_m')]),
            `${cm(r[col('gap_min_m')])} to ${cm(r[col('gap_max_m')])} (${r[col('n_gaps')]} gaps)`,
            `${r[col('n_cases')]} (${r[col('n_failed')]})`,
          ]),
      ),
      'data dsrss',
    );
    // d_req and d_SRSS over a numeric parameter (row number when there is none), one pair of
    // series per value of the others.
    const gx = groupCols.find((j) => body.every((r) => Number.isFinite(cellNumber(r[j]))));
    const xs = gx === undefined ? body.map((r, i) => i + 1) : columnNumbers(body, gx);
    const rest = groupCols.filter((j) => j !== gx);
    const keyOf = (r) => rest.map((j) => `${head[j]} = ${r[j]}`).join(', ');
    const series = [];
    for (const key of Array.from(new Set(body.map(keyOf)))) {
      const idx = body
        .map((r, i) => i)
        .filter((i) => keyOf(body[i]) === key)
        .sort((a, b) => xs[a] - xs[b]);
      const yOf = (n) => idx.map((i) => (body[i][col(n)] === '' ? null : parseFloat(body[i][col(n)]) * 100));
      const suffix = key ? `, ${key}` : '';
      series.push({ label: `d_req${suffix}`, x: idx.map((i) => xs[i]), y: yOf('d_req_m') });
      series.push({ label: `d_SRSS${suffix}`, x: idx.map((i) => xs[i]), y: yOf('d_srss_m'), dash: [6, 3] });
    }
    chart(sec, {
      title: 'required gap d_req and SRSS estimate d_SRSS',
      points: true,
      integerX: gx === undefined,
      xlabel: gx === undefined ? 'row of dsrss_table.csv' : head[gx],
      ylabel: 'gap (cm)',
      x: series[0].x,
      series: series,
    });
  }

  // ---- study: k(H), one chart per law, one series per impact velocity ---------------------------
  function kTableSection(parent, text) {
    const rows = parseCsv(text);
    if (rows.length < 2) return;
    const head = rows[0];
    const body = rows.slice(1);
    const col = (n) => head.indexOf(n);
    if (col('wall_height_m') < 0) return;
    const sec = section(parent, 'Impact stiffness against wall height, k(H)');
    const velocities =
      col('impact_velocity_m_per_s') < 0
        ? ['']
        : Array.from(new Set(body.map((r) => r[col('impact_velocity_m_per_s')]))).sort(
            (a, b) => parseFloat(a) - parseFloat(b),
          );
    for (const [law, unit, text] of [
      ['kelvin_voigt', 'kN_per_mm_per_m', 'kN/mm/m'],
      ['jankowski', 'kN_per_mm1.5_per_m', 'kN/mm^1.5/m'],
    ]) {
      const series = [];
      const add = (name, label, rowsOf, dash, color) => {
        const j = col(name);
        if (j < 0) return;
        const h = col('wall_height_m');
        const picked = rowsOf.filter((r) => r[j] !== '').sort((a, b) => parseFloat(a[h]) - parseFloat(b[h]));
        if (!picked.length) return;
        series.push({
          label: label,
          dash: dash,
          color: color,
          x: picked.map((r) => parseFloat(r[h])),
          y: picked.map((r) => parseFloat(r[j])),
        });
      };
      // One colour per impact velocity: solid for the study's materials, dashed for linear ones.
      velocities.forEach((v, k) => {
        const at = v === '' ? body : body.filter((r) => r[col('impact_velocity_m_per_s')] === v);
        const vText = v === '' ? '' : `v = ${fmt(parseFloat(v), 4)} m/s`;
        const material = col('material') >= 0 && at.length ? at[0][col('material')] : '';
        add(
          `${law}_${unit}`,
          `${vText || 'fitted'}${material ? ` (${material} materials)` : ''}`,
          at,
          undefined,
          COLORS[k % COLORS.length],
        );
        add(
          `linear_${law}_${unit}`,
          `${vText ? vText + ' ' : ''}(linear materials)`,
          at,
          [6, 3],
          COLORS[k % COLORS.length],
        );
      });
      // The thesis' value is one per height: from the first row of each height.
      const firstOfH = body.filter(
        (r, i) => body.findIndex((q) => q[col('wall_height_m')] === r[col('wall_height_m')]) === i,
      );
      add(`thesis_${law}_${unit}`, 'thesis', firstOfH, [2, 3], '#000');
      if (!series.length) continue;
      chart(sec, {
        title: `${law.replace('_', '-')} k(H)${velocities.length > 1 ? ' per impact velocity' : ''}`,
        points: true,
        xlabel: 'wall height H (m)',
        ylabel: `k (${text})`,
        x: series[0].x,
        series: series.map((s) => Object.assign(s, { unit: text })),
      });
    }
  }

  // ---- fit: the FEM force beside each fitted law, and the k of every variant with its unit ------
  function fitSection(parent, data) {
    const d = data.h5['fit.h5'].datasets;
    const variants = {};
    for (const k of Object.keys(d)) {
      const m = /^\/fit\/([^/]+)\/([^/]+)\/model_force\/value$/.exec(k);
      if (m) (variants[m[1]] = variants[m[1]] || []).push(m[2]);
    }
    const cases = Object.keys(variants);
    if (!cases.length) return;
    const sec = section(parent, 'Fitted impact laws against the FEM force');
    for (const c of cases) {
      const g = (v, n) => d[`/fit/${c}/${v}/${n}`];
      const first = variants[c][0];
      const t0 = g(first, 'contact_start') ? g(first, 'contact_start').data : 0;
      const ms = (ts) => ts.map((t) => (t - t0) * 1e3);
      const series = [
        {
          label: 'FEM',
          x: ms(g(first, 'fem_force/time').data),
          y: g(first, 'fem_force/value').data.map((f) => f * 1e-3),
          color: '#000',
        },
      ];
      for (const v of variants[c]) {
        const k = g(v, 'stiffness');
        const cor = g(v, 'cor');
        series.push({
          label: `${v} (k = ${k ? fmt(kUnit(k).value, 4) + ' ' + kUnit(k).unit : '?'}, ` +
            `COR ${cor ? fmt(cor.data, 3) : '?'})`,
          x: ms(g(v, 'model_force/time').data),
          y: g(v, 'model_force/value').data.map((f) => f * 1e-3),
          dash: [5, 3],
        });
      }
      const height = d[`/fit/${c}/wall_height`];
      chart(sec, {
        title: `${c}${height ? ` (H = ${fmt(height.data, 4)} m)` : ''}: FEM contact force and the fitted laws`,
        xlabel: 'time since the contact began (ms)',
        ylabel: 'contact force (kN/m)',
        x: series[0].x,
        series: series,
      });
    }
    const text = data.csv && data.csv['fit_table.csv'];
    if (!text) return;
    const rows = parseCsv(text);
    const head = rows[0];
    const col = (n) => head.indexOf(n);
    const unit = (r, n) => (col(n) >= 0 ? r[col(n)] : '');
    table(
      sec,
      [
        'case',
        'H (m)',
        'variant',
        'law',
        'k per metre',
        'k 95 % interval',
        'k of the wall width',
        'COR',
        'exponent',
        'normalised RMS',
        'status',
      ],
      rows
        .slice(1)
        .map((r) => [
          r[col('case')],
          r[col('wall_height_m')],
          r[col('variant')],
          r[col('law')],
          el('span', { class: 'fit-k', text: `${fmt(parseFloat(r[col('k_per_m')]), 4)} ${unit(r, 'k_per_m_unit')}` }),
          `${fmt(parseFloat(r[col('k_per_m_lower')]), 3)} to ` +
            `${fmt(parseFloat(r[col('k_per_m_upper')]), 3)} ${unit(r, 'k_per_m_unit')}`,
          `${fmt(parseFloat(r[col('k_total')]), 4)} ${unit(r, 'k_total_unit')}`,
          fmt(parseFloat(r[col('cor')]), 4),
          r[col('exponent')],
          fmt(parseFloat(r[col('normalised_rms')]), 3),
          r[col('status')],
        ]),
      'data fit-table',
    );
  }

  /** A stiffness dataset (N/m^n/m) in the kN/mm^n/m engineers read. */
  function kUnit(k) {
    const m = /^N\/m(\^([\d.]+))?\/m$/.exec(k.units || '');
    if (!m) return { value: k.data, unit: k.units };
    const n = m[2] ? Number(m[2]) : 1;
    return { value: k.data * Math.pow(1e-3, n) * 1e-3, unit: n === 1 ? 'kN/mm/m' : `kN/mm^${n}/m` };
  }

  // ---- entry point -----------------------------------------------------------------------------
  /**
   * The results page of one result directory (`data`, kimp report's JSON); `others` are more
   * runs' data overlaid on the same charts (their cases named "run: case").
   */
  function showResults(container, data, others) {
    container.innerHTML = '';
    charts.length = 0;
    animation = null;
    femAnimation = null;
    const files = Object.keys(data.h5 || {}).concat(Object.keys(data.csv || {}));
    container.appendChild(el('h1', { text: `kimp ${data.kind || 'results'}: ${data.title}` }));
    container.appendChild(el('p', { class: 'muted', text: `files: ${files.join(', ')}` }));
    if (data.h5 && data.h5['lumped.h5']) lumpedSection(container, data, others);
    if (data.kind === 'study') studySection(container, data);
    if (data.kind === 'fem' && data.summary) femSummarySection(container, data.summary);
    if (data.h5 && data.h5['fem.h5']) femSection(container, data);
    if (data.h5 && data.h5['collide.h5']) collideSection(container, data, others);
    if (data.h5 && data.h5['fit.h5']) fitSection(container, data);
    const csv = data.csv || {};
    if (csv['dsrss_table.csv']) dsrssSection(container, data);
    if (csv['sweep.csv']) sweepSection(container, data);
    if (csv['k_table.csv']) kTableSection(container, csv['k_table.csv']);
    // Charts of several columns: one chart per unit.
    const presets = {
      'k_table.csv': { chart: false },
      'fit_table.csv': { chart: false },
      'wall_sdof.csv': {
        x: 'wall_height_m',
        groups: [['stiffness_MN_per_m_per_m'], ['effective_mass_t_per_m'], ['frequency_Hz']],
      },
      'flexible_wall.csv': {
        x: 'wall_height_m',
        groups: [
          [
            'ratio_peak_base_acceleration',
            'ratio_peak_top_acceleration',
            'ratio_peak_impact_force',
            'ratio_peak_interstorey_drift',
          ],
        ],
      },
    };
    for (const [name, text] of Object.entries(csv)) {
      if (name === 'sweep.csv' || name === 'dsrss_table.csv') continue;
      csvSection(container, name, text, presets[name]);
    }
    for (const [file, h5] of Object.entries(data.h5 || {})) seriesSection(container, file, h5);
    if (data.summary) {
      const body = section(container, 'summary.json', false);
      body.appendChild(el('pre', { class: 'json', text: JSON.stringify(data.summary, null, 1) }));
    }
  }

  return {
    showResults: showResults,
    animation: () => animation,
    femAnimation: () => femAnimation,
    charts: () => charts,
    figureSvg: figureSvg,
    figurePdf: figurePdf,
    chartFigure: chartFigure,
    parseCsv: parseCsv,
    chart: chart,
    parseQuantity: parseQuantity,
    el: el,
    fmt: fmt,
  };
})();

if (typeof window !== 'undefined') window.kimp = kimp;
