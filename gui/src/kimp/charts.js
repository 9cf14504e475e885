// kimp results page: interactive charts (uPlot) with wheel zoom and a time cursor, and their
// export (SVG, PDF, CSV) drawn from the series data as one list of primitives, not from uPlot's
// canvas.
'use strict';

(function () {
  const {
    view, COLORS, el, INTEGER_INCRS, tickLabels, fmt, download, slug, niceTicks, csvName, splitUnit,
    escapeXml,
  } = kimp;

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
        {
          label: spec.xlabel,
          // A categorical x (a choice such as impact.law): 1..n with the categories as labels.
          values: spec.xCategories
            ? (u, splits) => splits.map((v) => (Number.isInteger(v) ? spec.xCategories[v - 1] || '' : ''))
            : tickLabels,
          space: 50,
          incrs: spec.integerX || spec.xCategories ? INTEGER_INCRS : undefined,
        },
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
      categories: spec.xCategories || null,
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
        else if (view.animation) view.animation.seek(t);
      });
    }
    view.charts.push(c);
    return c;
  }

  // Printing: every chart at most the width of an A4 page's text (about 680 CSS px at the
  // browser's default margins), its screen width back afterwards.
  const PRINT_WIDTH = 680;
  if (typeof window !== 'undefined') {
    window.addEventListener('beforeprint', () => {
      for (const c of view.charts) {
        c.screenWidth = c.plot.width;
        if (c.plot.width > PRINT_WIDTH) c.plot.setSize({ width: PRINT_WIDTH, height: c.plot.height });
      }
    });
    window.addEventListener('afterprint', () => {
      for (const c of view.charts)
        if (c.screenWidth) c.plot.setSize({ width: c.screenWidth, height: c.plot.height });
    });
  }

  function setTimeCursor(t) {
    for (const c of view.charts) {
      if (!c.cursor || !c.plot.scales.x) continue;
      const x = c.plot.valToPos(t, 'x');
      c.cursor.style.display = x >= 0 && x <= c.plot.over.clientWidth ? 'block' : 'none';
      c.cursor.style.left = x + 'px';
    }
  }

  Object.assign(kimp, { chartFigure, figureSvg, figurePdf, chart, setTimeCursor });
})();
