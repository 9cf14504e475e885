// kimp results page: the study, collide, sweep, k-table and fit sections, and the entry point
// showResults() of one result directory, optionally overlaid with other runs.
'use strict';

(function () {
  const {
    view, COLORS, el, fmt, parseCsv, seriesGroups, chart, section, table, columnTable, cellNumber, cellUnit,
    columnNumbers, csvSection, seriesSection, lumpedSection, planSection, femSection, femSummarySection, DISPLAY_UNITS,
    units, setDisplayUnit,
  } = kimp;

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
    // A parameter whose values carry different units (the k of paired laws: kN/mm, kN/mm^1.5) is
    // not an axis.
    const oneUnit = (j) => new Set(body.map((r) => (/[A-Za-z%][^\s]*\s*$/.exec(r[j]) || [''])[0])).size === 1;
    const numericParam = params.filter(
      (j) => body.every((r) => r[j] === '' || Number.isFinite(cellNumber(r[j]))) && oneUnit(j),
    );
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
    // d_req and d_SRSS over a numeric parameter, else over the first parameter's values as
    // categories (impact.law), one pair of series per value of the others.
    const gx = groupCols.find((j) => body.every((r) => Number.isFinite(cellNumber(r[j]))));
    const categorical = gx === undefined && groupCols.length ? groupCols[0] : undefined;
    const categories = categorical === undefined ? null : Array.from(new Set(body.map((r) => r[categorical])));
    const xs =
      gx !== undefined
        ? columnNumbers(body, gx)
        : categories
          ? body.map((r) => categories.indexOf(r[categorical]) + 1)
          : body.map((r, i) => i + 1);
    const xCol = gx !== undefined ? gx : categorical;
    const rest = groupCols.filter((j) => j !== xCol);
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
    const xUnit = gx === undefined ? '' : cellUnit(body, gx);
    chart(sec, {
      title: 'required gap d_req and SRSS estimate d_SRSS',
      points: true,
      integerX: gx === undefined,
      xCategories: categories,
      xlabel:
        xCol === undefined ? 'row of dsrss_table.csv' : xUnit ? `${head[xCol]} (${xUnit})` : head[xCol],
      ylabel: 'gap (cm)',
      x: series[0].x,
      series: series,
    });
  }

  // ---- study: the answer first, k at the reference velocity per wall height -------------------
  /**
   * The study's k at its reference velocity (the k of its building runs), one row per wall
   * height, with how well each fit reproduces the FEM peak force and the fits' status: the first
   * section of a study's page.
   */
  function kAnswerSection(parent, text) {
    const rows = parseCsv(text);
    if (rows.length < 2) return;
    const head = rows[0];
    const col = (n) => head.indexOf(n);
    if (col('wall_height_m') < 0) return;
    const reference = col('reference_velocity');
    const body = rows.slice(1).filter((r) => reference < 0 || r[reference] === 'yes');
    const cell = (r, n, digits) => (col(n) >= 0 && r[col(n)] !== '' ? fmt(parseFloat(r[col(n)]), digits) : '-');
    const status = (r) => {
      const kv = r[col('kelvin_voigt_status')] || '';
      const j = r[col('jankowski_status')] || '';
      return kv === 'ok' && j === 'ok' ? 'ok' : `Kelvin-Voigt: ${kv}; Jankowski: ${j}`;
    };
    const sec = section(parent, 'Impact stiffness k (the answer: reference velocity)');
    table(
      sec,
      [
        'H (m)',
        'v (m/s)',
        'KV k (kN/mm/m)',
        'KV k total (kN/mm)',
        'KV fit/FEM peak',
        'Jankowski k (kN/mm^1.5/m)',
        'J k total (kN/mm^1.5)',
        'J fit/FEM peak',
        'fit status',
      ],
      body.map((r) => [
        cell(r, 'wall_height_m', 4),
        cell(r, 'impact_velocity_m_per_s', 4),
        cell(r, 'kelvin_voigt_kN_per_mm_per_m', 4),
        cell(r, 'kelvin_voigt_total_kN_per_mm', 4),
        cell(r, 'kelvin_voigt_peak_force_ratio', 3),
        cell(r, 'jankowski_kN_per_mm1.5_per_m', 4),
        cell(r, 'jankowski_total_kN_per_mm1.5', 4),
        cell(r, 'jankowski_peak_force_ratio', 3),
        status(r),
      ]),
      'data k-answer',
    );
  }

  // ---- study: the yielding walls first ----------------------------------------------------------
  /**
   * With inelastic materials the study's answer is each building run's wall against its yielding
   * wall element: the element's source (pushover or estimate) and yield force, the peak wall
   * resistance against it, the peak and residual wall displacement and whether the wall failed
   * (yielding_wall.csv, yielding_wall_element.csv). The k table then follows as the comparison
   * with Table 2.1. A linear study (`route` "linear" in summary.json) runs the same building
   * runs against each height's estimate element beside its impact springs: the same table,
   * titled as the estimate.
   */
  function yieldingWallAnswerSection(parent, runsText, elementsText, route) {
    const runs = parseCsv(runsText);
    if (runs.length < 2) return;
    const head = runs[0];
    const col = (n) => head.indexOf(n);
    if (col('wall_height_m') < 0) return;
    const elements = elementsText ? parseCsv(elementsText) : [];
    const eHead = elements[0] || [];
    const elementValue = (h, name) => {
      const row = elements.slice(1).find((r) => r[eHead.indexOf('wall_height_m')] === h);
      return row && eHead.indexOf(name) >= 0 ? row[eHead.indexOf(name)] : '-';
    };
    const source = (h) => elementValue(h, 'source');
    const cell = (r, n, digits) => (col(n) >= 0 && r[col(n)] !== '' ? fmt(parseFloat(r[col(n)]), digits) : '-');
    const linear = route === 'linear';
    const sec = section(
      parent,
      linear
        ? 'Moat walls as yielding elements (estimate, beside the linear springs): capacity and residual displacement'
        : 'Yielding moat walls (the answer with inelastic materials)',
    );
    columnTable(
      sec,
      [
        ['record', (r) => r[col('record')]],
        ['H (m)', (r) => cell(r, 'wall_height_m', 4)],
        ['element from', (r) => source(r[col('wall_height_m')])],
        ['envelope', (r) => elementValue(r[col('wall_height_m')], 'envelope')],
        ['capacity (kN/m)', (r) => cell(r, 'wall_capacity_per_metre_kN_per_m', 4)],
        ['capacity W (kN)', (r) => cell(r, 'wall_capacity_kN', 4)],
        ['peak wall resistance (kN)', (r) => cell(r, 'peak_wall_resistance_kN', 4)],
        ['resistance / capacity W', (r) => cell(r, 'resistance_over_capacity', 3)],
        ['peak wall displacement (cm)', (r) => cell(r, 'peak_wall_displacement_cm', 4)],
        ['residual (cm)', (r) => cell(r, 'residual_wall_displacement_cm', 4)],
        ['failed', (r) => (r[col('failed')] === '1' ? `yes, at ${cell(r, 'failure_time_s', 4)} s` : 'no')],
        ['status', (r) => r[col('status')]],
      ],
      runs.slice(1),
      'data yielding-answer',
      2,
    );
    sec.appendChild(
      el('p', {
        class: 'muted',
        text:
          (linear
            ? 'A linear study: its building runs hit impact springs that never yield; these are the ' +
              'same runs against each height\'s estimate element (capacity (M_p + P_p H/3)/h_c from ' +
              'the wall\'s section and the passive resistance of its backfill, cracked cantilever ' +
              'stiffness, radiation dashpot rho c; no FEM pushover). '
            : '') +
          'capacity W: the wall-and-backfill part\'s capacity over the building width. On a hull ' +
          '(the pushover\'s concave hull) it is the largest force, flat past it; on a bilinear it ' +
          'is F_y, past which the wall hardens with the pushover\'s slope, so the ratio may exceed 1 ' +
          'without failure. The k table below is the comparison with Table 2.1.',
      }),
    );
  }

  // ---- study: k(H), one chart per law, one series per impact velocity ---------------------------
  function kTableSection(parent, text) {
    const rows = parseCsv(text);
    if (rows.length < 2) return;
    const head = rows[0];
    const body = rows.slice(1);
    const col = (n) => head.indexOf(n);
    if (col('wall_height_m') < 0) return;
    // One wall height (a site): a chart against H would plot one point; the answer table above
    // holds the values.
    if (new Set(body.map((r) => r[col('wall_height_m')])).size < 2) return;
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
    const number = (r, n, digits) => fmt(parseFloat(r[col(n)]), digits);
    columnTable(
      sec,
      [
        ['case', (r) => r[col('case')]],
        ['H (m)', (r) => r[col('wall_height_m')]],
        ['variant', (r) => r[col('variant')]],
        ['law', (r) => r[col('law')]],
        [
          'k per metre',
          (r) => el('span', { class: 'fit-k', text: `${number(r, 'k_per_m', 4)} ${unit(r, 'k_per_m_unit')}` }),
        ],
        [
          'k 95 % interval',
          (r) => `${number(r, 'k_per_m_lower', 3)} to ${number(r, 'k_per_m_upper', 3)} ${unit(r, 'k_per_m_unit')}`,
        ],
        ['k of the wall width', (r) => `${number(r, 'k_total', 4)} ${unit(r, 'k_total_unit')}`],
        ['COR', (r) => number(r, 'cor', 4)],
        ['exponent', (r) => r[col('exponent')]],
        ['normalised RMS', (r) => number(r, 'normalised_rms', 3)],
        ['status', (r) => r[col('status')]],
      ],
      rows.slice(1),
      'data fit-table',
    );
  }

  // ---- export-opensees: what was exported, where each value came from, and the files ---------
  function exportSection(parent, data) {
    const summary = data.summary || {};
    const input = summary.input || {};
    const sources = summary.sources || {};
    const units = summary.units || {};
    const sec = section(parent, 'OpenSees materials exported');
    const rows = [
      ['k_KV', 'k_kelvin_voigt', 'k'],
      ['k_J', 'k_hertz', 'k'],
      ['COR e', 'cor', 'cor'],
      ['m_eff', 'effective_mass', 'effective_mass'],
      ['v_imp', 'impact_velocity', 'impact_velocity'],
      ['gap', 'gap', 'gap'],
    ]
      .filter(([, key]) => input[key] !== null && input[key] !== undefined)
      .map(([label, key, source]) => [
        label,
        `${fmt(input[key], 6)} ${units[key] || ''}`.trim(),
        sources[source] || '',
      ]);
    table(sec, ['parameter', 'value (SI)', 'from'], rows, 'data export-parameters');
    for (const [name, text] of Object.entries(data.text || {})) {
      const body = section(parent, name);
      body.appendChild(el('pre', { class: 'export-file', text: text }));
    }
  }

  /** A stiffness dataset (N/m^n/m) in the kN/mm^n/m engineers read (MN/m/m when chosen, n = 1). */
  function kUnit(k) {
    const m = /^N\/m(\^([\d.]+))?\/m$/.exec(k.units || '');
    if (!m) return { value: k.data, unit: k.units };
    const n = m[2] ? Number(m[2]) : 1;
    const linear = units.stiffness === 'MN/m' ? 'MN/m/m' : 'kN/mm/m';
    return { value: k.data * Math.pow(1e-3, n) * 1e-3, unit: n === 1 ? linear : `kN/mm^${n}/m` };
  }

  // ---- display units and inputs ---------------------------------------------------------------
  /** The reader's choice of display units; a change redraws the page (`redraw`). */
  function unitsBar(container, redraw) {
    const names = { acceleration: 'acceleration', force: 'force', length: 'displacement', stiffness: 'stiffness' };
    const picks = Object.keys(DISPLAY_UNITS).map((kind) => {
      const pick = el(
        'select',
        { class: 'unit-pick', 'data-kind': kind },
        Object.keys(DISPLAY_UNITS[kind]).map((u) => el('option', { value: u, text: u })),
      );
      pick.value = units[kind];
      pick.addEventListener('change', () => {
        setDisplayUnit(kind, pick.value);
        redraw();
      });
      return el('label', { text: names[kind] + ' ' }, [pick]);
    });
    container.appendChild(el('div', { class: 'controls units-bar' }, [el('span', { text: 'units: ' }), ...picks]));
  }

  /** The inputs of the run: the scene as run (/input/scene of its results file), verbatim. */
  function inputsSection(container, data) {
    for (const [file, h5] of Object.entries(data.h5 || {})) {
      const scene = (h5.datasets || {})['/input/scene'];
      if (!scene || typeof scene.data !== 'string') continue;
      const body = section(container, `Inputs: the scene as run (${file} /input/scene)`, false);
      body.appendChild(el('pre', { class: 'json inputs-scene', text: scene.data }));
      return;
    }
  }

  // ---- entry point -----------------------------------------------------------------------------
  /**
   * The results page of one result directory (`data`, kimp report's JSON); `others` are more
   * runs' data overlaid on the same charts (their cases named "run: case").
   */
  function showResults(container, data, others) {
    container.innerHTML = '';
    view.charts.length = 0;
    view.animation = null;
    view.femAnimation = null;
    const files = Object.keys(data.h5 || {}).concat(Object.keys(data.csv || {}));
    container.appendChild(el('h1', { text: `kimp ${data.kind || 'results'}: ${data.title}` }));
    container.appendChild(el('p', { class: 'muted', text: `files: ${files.join(', ')}` }));
    unitsBar(container, () => showResults(container, data, others));
    const kTable = data.csv && data.csv['k_table.csv'];
    const yielding = data.csv && data.csv['yielding_wall.csv'];
    if (data.kind === 'study' && yielding)
      yieldingWallAnswerSection(
        container,
        yielding,
        data.csv['yielding_wall_element.csv'],
        data.summary && data.summary.yielding_wall && data.summary.yielding_wall.route,
      );
    if (data.kind === 'study' && kTable) kAnswerSection(container, kTable);
    inputsSection(container, data);
    // A run in plan (a scene with `plan:`) has its own view: directions, rotation, the plan view.
    const inPlan = data.summary && data.summary.plan;
    if (data.h5 && data.h5['lumped.h5']) (inPlan ? planSection : lumpedSection)(container, data, others);
    if (data.kind === 'study') studySection(container, data);
    if (data.kind === 'fem' && data.summary) femSummarySection(container, data.summary);
    if (data.h5 && data.h5['fem.h5']) femSection(container, data);
    if (data.h5 && data.h5['collide.h5']) collideSection(container, data, others);
    if (data.h5 && data.h5['fit.h5']) fitSection(container, data);
    if (data.kind === 'export-opensees') exportSection(container, data);
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

  // The page's interface to gui.js and the browser tests (with figureSvg, chart, ... of the
  // other files).
  Object.assign(kimp, {
    showResults,
    animation: () => view.animation,
    femAnimation: () => view.femAnimation,
    charts: () => view.charts,
  });
})();

if (typeof window !== 'undefined') window.kimp = kimp;
