// kimp results page: collapsible sections, tables with units, a chart per unit of a CSV table, and
// the time series of a results file.
'use strict';

(function () {
  const { el, fmt, parseCsv, parseQuantity, column, seriesGroups, chart } = kimp;

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

  /**
   * A table in a horizontally scrolling box; its first `pin` columns (the key ones) stay in view
   * while the others scroll (sticky cells, their offsets measured once laid out).
   */
  function table(parent, header, rows, cls, pin) {
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
    if (pin > 0) {
      t.classList.add('pinned');
      const place = () => {
        const first = t.rows[0];
        if (!first || !first.cells[0].offsetWidth) return;
        let left = 0;
        for (let j = 0; j < pin && j < first.cells.length; ++j) {
          for (const r of t.rows) {
            const cell = r.cells[j];
            if (!cell) continue;
            cell.classList.add('pin');
            cell.style.left = left + 'px';
          }
          left += first.cells[j].offsetWidth;
        }
      };
      if (typeof ResizeObserver !== 'undefined') new ResizeObserver(place).observe(t);
      place();
    }
    return t;
  }

  /**
   * table() of `rows` whose columns are [heading, cell of a row] pairs, so that each heading
   * stands beside the value under it.
   */
  function columnTable(parent, columns, rows, cls, pin) {
    const header = columns.map(([heading]) => heading);
    return table(parent, header, rows.map((r) => columns.map(([, cell]) => cell(r))), cls, pin);
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

  /**
   * A peak of a results table: 4 significant figures of `v × scale` on the page, the SI value in
   * full in data-si (as in summary.json), `key` naming it for the tests and the unit switch.
   */
  function peakCell(v, scale, key) {
    return el('span', {
      class: 'peak',
      'data-key': key,
      'data-si': String(v),
      'data-scale': String(scale),
      text: fmt(v * scale, 4),
    });
  }

  Object.assign(kimp, {
    section, table, columnTable, cellNumber, cellUnit, columnNumbers, csvSection, seriesSection, peakCell,
  });
})();
