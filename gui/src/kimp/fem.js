// kimp results page: the FEM impact (kimp fem): the deformed mesh over the impact coloured by a
// field, and the summary of every case in engineering units (4 significant figures).
'use strict';

(function () {
  const { view, el, fmt, download, escapeXml, chart, setTimeCursor, section, table, makePlayer } = kimp;

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
    const caseSel = el(
      'select',
      { class: 'fem-case' },
      names.map((n) => el('option', { value: n, text: n })),
    );
    const fieldSel = el('select', { class: 'fem-field' });
    const W = 900;
    const H = 440;
    const player = makePlayer(body, {
      prefix: 'fem',
      width: W,
      height: H,
      svgClass: 'fem-animation',
      speeds: [0.25, 0.5, 1, 2, 4],
      exaggeration: { max: 100000, value: 1 },
      label: { text: '' },
      scrubMax: 0,
      leading: [el('label', { text: 'case ' }, [caseSel]), el('label', { text: ' colour by ' }, [fieldSel])],
    });
    const { svg, speed, scrub, exportFrame, label } = player;
    const exag = player.exaggeration;
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

    let carry = 0; // frames to advance, 10 per second at speed 1
    const { play: start, pause } = player.run(state, {
      step: (ms) => {
        carry += (ms / 100) * Number(speed.value);
        while (carry >= 1 && state.frame < state.mesh.time.length - 1) {
          carry -= 1;
          state.frame += 1;
        }
      },
      atEnd: () => state.frame >= state.mesh.time.length - 1,
      rewind: () => {
        state.frame = 0;
      },
      onPlay: () => {
        carry = 0;
      },
      draw: () => draw(),
    });
    const api = {
      state: state,
      play: start,
      pause: pause,
      seek: (i) => {
        state.frame = Math.max(0, Math.min(i, state.mesh.time.length - 1));
        draw();
      },
      /** The frame nearest to time t (s). */
      seekTime: (t) => {
        const ts = state.mesh.time;
        let best = 0;
        for (let k = 1; k < ts.length; ++k) if (Math.abs(ts[k] - t) < Math.abs(ts[best] - t)) best = k;
        api.seek(best);
      },
      time: () => state.mesh.time[state.frame],
      frameSvg: player.frameSvg,
    };
    caseSel.addEventListener('change', () => setCase(caseSel.value));
    fieldSel.addEventListener('change', draw);
    exag.addEventListener('change', draw);
    scrub.addEventListener('input', () => api.seek(Number(scrub.value)));
    exportFrame.addEventListener('click', () =>
      download(`${state.mesh.name}_frame${state.frame}.svg`, api.frameSvg(), 'image/svg+xml'),
    );
    setCase(names[0]);
    view.femAnimation = api;
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
    ['first_peak_force', 'first peak force (kN/m)', 1e-3],
    ['first_peak_time', 'first peak after contact (ms)', 1e3],
    ['first_peak_impulse', 'impulse of the first pulse (N·s/m)', 1],
    ['max_slab_displacement', 'largest slab travel (mm)', 1e3],
    ['max_wall_displacement', 'largest wall displacement (mm)', 1e3],
    ['energy_equivalent_resistance', 'energy-equivalent resistance E₀/travel (kN/m)', 1e-3],
    ['time_to_95_travel', 'time to stop the slab: to 95 % of its travel (ms)', 1e3],
    ['time_to_stop', 'slab velocity zero (ms)', 1e3],
    ['max_bar_strain_ratio', 'largest bar strain / yield strain at a point (mesh-dependent)', 1],
    ['max_bar_strain_height', 'its height above the ground (m)', 1],
    ['bars_yield', 'bars yield', null],
    ['max_bar_gauge_strain_ratio', 'largest vertical bar strain over the gauge / yield strain', 1],
    ['max_bar_gauge_strain_height', "the gauge's centre above the ground (m)", 1],
    ['bar_gauge_length', 'gauge length (m)', 1],
    ['bars_yield_over_gauge', 'bars yield over the gauge', null],
    ['impulse_momentum_ratio', '∫F dt / m(v_in + v_out)', 1],
    ['impulse_momentum', 'impulse-momentum check', null],
    ['max_penetration', 'largest penetration (mm)', 1e3],
    ['permanent_indentation', 'permanent indentation (mm)', 1e3],
    ['wall_residual_displacement', 'wall face at the end (mm)', 1e3],
    ['plastic_dissipation', 'plastic dissipation (J/m)', 1],
    ['plastic_dissipation_slab', 'plastic dissipation in the slab (J/m)', 1],
    ['plastic_dissipation_wall', 'plastic dissipation in the wall (J/m)', 1],
    ['plastic_dissipation_soil', 'plastic dissipation in the soil (J/m)', 1],
    ['damage_dissipation', 'damage dissipation (J/m)', 1],
    ['damage_dissipation_slab', 'damage dissipation in the slab (J/m)', 1],
    ['damage_dissipation_wall', 'damage dissipation in the wall (J/m)', 1],
    ['contact_dissipation', 'contact dissipation (J/m)', 1],
    ['radiated_energy', 'radiated energy (J/m)', 1],
    ['slab_damping_dissipation', "work of the slab's damping (J/m)", 1],
    ['boundary_spring_energy', "energy in the far boundary's springs (J/m)", 1],
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

  Object.assign(kimp, { femSection, femSummarySection });
})();
