// kimp results page: a lumped run in plan (a scene with `plan:`): headline peaks, histories per
// direction (x, y) and rotation per level, the base corners' displacements, contact forces, the
// energy balance with friction work, and the plan view (slab, moat wall, contact points) animated.
'use strict';

(function () {
  const { view, el, fmt, column, seriesGroups, chart, section, table, displayUnit, escapeXml } = kimp;
  const { peakCell, historyViews, historyPlayer } = kimp;

  /** The plan run's one case: {summary, label, history, geometry} from lumped.h5 and summary.json. */
  function planCase(data) {
    const h5 = data.h5['lumped.h5'];
    const s = data.summary.cases[0];
    const prefix = `/lumped/${s.name}/`;
    const history = {};
    for (const g of seriesGroups(h5)) {
      if (g.path.startsWith(prefix + 'history/')) {
        const v = g.series.find((x) => x.name === 'value');
        if (v) history[g.path.slice(prefix.length + 8)] = { time: g.time, values: v.values };
      }
    }
    const ds = (name) => h5.datasets[prefix + name];
    const data2 = (name) => (ds(name) && Array.isArray(ds(name).data) ? ds(name).data : null);
    const names = data2('contact_names') || [];
    return {
      summary: s,
      label: s.name,
      history: history,
      labels: data2('dof_labels') || [],
      contacts: names,
      geometry: {
        slab: data2('plan/slab_outline'),
        reference: data2('plan/slab_reference') || [0, 0],
        wall: data2('plan/wall'),
        contacts: data2('plan/contact_position') || [],
      },
    };
  }

  /** Displacement (x, y) of the material point p of level 0 under its DoFs q = [u_x, u_y, θ]. */
  function pointDisplacement(p, ref, q) {
    return [q[0] - (p[1] - ref[1]) * q[2], q[1] + (p[0] - ref[0]) * q[2]];
  }

  /** The point of the closed polygon `poly` nearest to p. */
  function nearestOnPolygon(poly, p) {
    let best = null;
    let bestD = Infinity;
    for (let i = 0; i < poly.length; ++i) {
      const a = poly[i];
      const b = poly[(i + 1) % poly.length];
      const dx = b[0] - a[0];
      const dy = b[1] - a[1];
      const t = Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy || 1)));
      const q = [a[0] + t * dx, a[1] + t * dy];
      const d = Math.hypot(p[0] - q[0], p[1] - q[1]);
      if (d < bestD) {
        bestD = d;
        best = q;
      }
    }
    return best;
  }

  function peaksSection(parent, c) {
    const s = c.summary;
    const [L, lengthUnit] = displayUnit('length');
    const [A, accelerationUnit] = displayUnit('acceleration');
    const [F, forceUnit] = displayUnit('force');
    const cell = peakCell;
    const p = s.peaks;
    const columns = [
      [`peak corner impact force (${forceUnit})`, p.corner_impact_force, F, 'corner_impact_force'],
      [`peak friction force (${forceUnit})`, p.friction_force, F, 'friction_force'],
      [`peak base corner displacement (${lengthUnit})`, p.base_corner_displacement, L, 'base_corner_displacement'],
      ['peak rotation (rad)', p.rotation, 1, 'rotation'],
      [`max corner drift (${lengthUnit})`, p.corner_drift, L, 'corner_drift'],
      [`peak top acceleration (${accelerationUnit})`, p.top_acceleration, A, 'top_acceleration'],
      [`peak isolator force (${forceUnit})`, p.isolator_force, F, 'isolator_force'],
    ];
    const body = section(parent, 'Peaks in plan (summary.json)');
    table(
      body,
      ['case', 'status'].concat(columns.map((x) => x[0])).concat(['impacts']),
      [
        [c.label, s.status]
          .concat(columns.map(([, v, scale, key]) => cell(v, scale, `${s.name}.${key}`)))
          .concat([String(s.n_impacts)]),
      ],
      'data peaks',
      1,
    );
    return body;
  }

  /** The superstructure's damping model (summary.json `damping`: model, ζ, ζ_iso), one line. */
  function dampingLine(parent, c) {
    const d = c.summary.damping;
    if (!d) return;
    const zeta = `ζ = ${fmt(100 * d.damping_ratio, 3)} %`;
    const text =
      d.model === 'modal'
        ? `Damping: modal, ${zeta} in every mode of the coupled building (x, y and θ together)`
        : `Damping: Rayleigh per direction, ${zeta} at the first and last mode of each direction`;
    parent.appendChild(
      el('p', {
        class: 'muted damping',
        'data-model': d.model,
        text: `${text}; isolation level ζ_iso = ${fmt(100 * d.isolation_damping_ratio, 3)} %.`,
      }),
    );
  }

  /**
   * The yielding wall faces (summary.json `yielding_walls`): per face its peak contact force, the
   * wall-and-backfill part's peak resistance against its capacity, peak and residual displacement,
   * and whether (and when) it failed.
   */
  function yieldingSection(parent, c) {
    const faces = c.summary.yielding_walls;
    if (!faces || !faces.length) return;
    const [F, forceUnit] = displayUnit('force');
    const [L, lengthUnit] = displayUnit('length');
    const cell = peakCell;
    const sec = section(parent, 'Yielding wall faces');
    table(
      sec,
      [
        'face',
        `peak face force (${forceUnit})`,
        `capacity (${forceUnit})`,
        `peak resistance (${forceUnit})`,
        'resistance / capacity',
        `peak wall displacement (${lengthUnit})`,
        `residual (${lengthUnit})`,
        'failed',
      ],
      faces.map((w) => [
        String(w.face),
        cell(w.peak_force, F, `face_${w.face}.peak_force`),
        cell(w.capacity, F, `face_${w.face}.capacity`),
        cell(w.peak_resistance, F, `face_${w.face}.peak_resistance`),
        fmt(w.peak_resistance_ratio, 3),
        cell(w.peak_displacement, L, `face_${w.face}.peak_displacement`),
        cell(w.residual_displacement, L, `face_${w.face}.residual_displacement`),
        w.failed ? `yes, at ${fmt(w.failure_time, 4)} s` : 'no',
      ]),
      'data yielding-faces',
      1,
    );
    sec.appendChild(
      el('p', {
        class: 'muted',
        text:
          'Face k: wall corner k to k + 1 counter-clockwise. Capacity and resistance are the ' +
          "wall-and-backfill part's (per metre × the face's length); past the capacity the wall " +
          'hardens, so the ratio may exceed 1 without failure.',
      }),
    );
  }

  /** Histories: x and y per level, rotation per level, base corners, contact and friction forces. */
  function historySection(parent, c) {
    const body = section(parent, 'Histories in plan');
    const [L, lengthUnit] = displayUnit('length');
    const [F, forceUnit] = displayUnit('force');
    const d = c.history.displacement;
    const nLevels = d.values[0].length / 3;
    const level = (l) => c.labels[3 * l].replace(/ x$/, '');
    const perLevel = (dir, scale) =>
      Array.from({ length: nLevels }, (_, l) => ({
        label: level(l),
        y: column(d.values, 3 * l + dir).map((v) => v * scale),
      }));
    const opts = { xlabel: 'time (s)', time: true, x: d.time };
    chart(body, { ...opts, title: 'displacement along x', ylabel: `u_x (${lengthUnit})`, series: perLevel(0, L) });
    chart(body, { ...opts, title: 'displacement along y', ylabel: `u_y (${lengthUnit})`, series: perLevel(1, L) });
    chart(body, { ...opts, title: 'rotation', ylabel: 'θ (rad)', series: perLevel(2, 1) });
    const corners = c.history.corner_displacement;
    if (corners) {
      const n = corners.values[0].length / 2;
      chart(body, {
        xlabel: 'time (s)',
        time: true,
        x: corners.time,
        title: 'base corner displacements',
        ylabel: `|u| of the corner (${lengthUnit})`,
        series: Array.from({ length: n }, (_, k) => ({
          label: `corner ${k}`,
          y: corners.values.map((row) => Math.hypot(row[2 * k], row[2 * k + 1]) * L),
        })),
      });
    }
    for (const [key, title] of [
      ['contact_force', 'contact normal force'],
      ['friction_force', 'contact friction force'],
    ]) {
      const h = c.history[key];
      if (!h) continue;
      chart(body, {
        xlabel: 'time (s)',
        time: true,
        x: h.time,
        title: title,
        ylabel: `${title} (${forceUnit})`,
        series: c.contacts.map((name, k) => ({ label: name, y: column(h.values, k).map((v) => v * F) })),
      });
    }
  }

  /** Where the input energy went (summary.json), friction work as its own term when present. */
  function energySection(parent, c) {
    const e = c.summary.energy;
    if (!e) return;
    const terms = [
      ['input', e.input],
      ['kinetic', e.kinetic],
      ['strain', e.strain],
      ['viscous', e.viscous],
      ['hysteretic', e.hysteretic],
      ['impact dissipated', e.impact_dissipated],
    ];
    if (e.friction !== undefined) terms.push(['friction work', e.friction]);
    if (c.summary.yielding_walls && c.summary.yielding_walls.length)
      terms.push(['wall plastic', e.wall_plastic], ['wall radiated', e.wall_radiated]);
    const body = section(parent, 'Energy balance');
    chart(body, {
      title: 'energy balance',
      xlabel: 'term',
      ylabel: 'energy (MJ)',
      points: true,
      xCategories: terms.map((t) => t[0]),
      x: terms.map((_, i) => i + 1),
      series: [{ label: c.label, y: terms.map((t) => t[1] * 1e-6) }],
    });
    body.appendChild(
      el('p', {
        class: 'muted',
        text: `balance residual ${fmt(e.relative_error, 3)} of the input energy (largest over the run ${fmt(
          e.max_relative_error,
          3,
        )})`,
      }),
    );
  }

  /** The plan view: level 0's outline displaced, the moat wall, contact points flashing in contact. */
  function planAnimation(parent, c) {
    const { width: W, height: H } = historyViews.plan;
    const g = c.geometry;
    const all = g.slab.concat(g.wall || []);
    const [x0, x1] = [Math.min(...all.map((p) => p[0])), Math.max(...all.map((p) => p[0]))];
    const [y0, y1] = [Math.min(...all.map((p) => p[1])), Math.max(...all.map((p) => p[1]))];
    const margin = 0.25 * Math.max(x1 - x0, y1 - y0);
    const scale = Math.min((W - 40) / (x1 - x0 + 2 * margin), (H - 60) / (y1 - y0 + 2 * margin));
    const cx = (x0 + x1) / 2;
    const cy = (y0 + y1) / 2;
    // Plan coordinates (y up) to the canvas.
    const px = (p) => [W / 2 + (p[0] - cx) * scale, 30 + (H - 30) / 2 - (p[1] - cy) * scale];
    const pts = (poly) => poly.map((p) => px(p).map((v) => v.toFixed(1)).join(',')).join(' ');
    /** Level 0 at history sample i. */
    function frame(i, tText) {
      const e = api.state.exaggeration;
      const q = c.history.displacement.values[i].slice(0, 3);
      const moved = (p) => {
        const u = pointDisplacement(p, g.reference, q);
        return [p[0] + e * u[0], p[1] + e * u[1]];
      };
      const parts = [];
      if (g.wall) {
        // The wall's clear gap drawn `exaggeration` times wider, as the displacements are.
        const wall = g.wall.map((w) => {
          const n = nearestOnPolygon(g.slab, w);
          return [n[0] + e * (w[0] - n[0]), n[1] + e * (w[1] - n[1])];
        });
        parts.push(`<polygon class="wall" points="${pts(wall)}" fill="none" stroke="#777" stroke-width="8"/>`);
      }
      parts.push(
        `<polygon class="slab-rest" points="${pts(g.slab)}" fill="none" stroke="#bbb" stroke-dasharray="6 4"/>`,
      );
      parts.push(
        `<polygon class="slab" points="${pts(g.slab.map(moved))}" fill="#cde" fill-opacity="0.6" stroke="#123" ` +
          'stroke-width="3"/>',
      );
      const f = c.history.contact_force ? c.history.contact_force.values[i] : [];
      const peaks = c.summary.peaks;
      g.contacts.forEach((p, k) => {
        const [x, y] = px(moved(p));
        const force = f[k] || 0;
        const on = force > 0;
        const r = on ? 5 + 20 * Math.sqrt(force / Math.max(peaks.corner_impact_force, 1)) : 4;
        parts.push(
          `<circle class="contact${on ? ' active' : ''}" data-contact="${escapeXml(c.contacts[k] || '')}" ` +
            `cx="${x.toFixed(1)}" cy="${y.toFixed(1)}" r="${r.toFixed(1)}" fill="${on ? '#e00' : '#555'}" ` +
            `fill-opacity="${on ? 0.6 : 1}"/>`,
        );
        if (on) {
          parts.push(
            `<text class="impact-label" x="${(x + r + 3).toFixed(1)}" y="${(y + 4).toFixed(1)}" font-size="13" ` +
              `fill="#b00">${fmt(force * 1e-6, 3)} MN</text>`,
          );
        }
      });
      parts.push(
        `<text x="10" y="20" font-size="14">${escapeXml(c.label)} in plan: t = ${tText} s, level 0 ` +
          `displacements and gaps ×${e}</text>`,
      );
      return parts.join('');
    }

    const api = historyPlayer(parent, 'plan', frame);
    api.setCase(c);
    return api;
  }

  /** The results of a lumped run in plan (summary.json `plan: true`). */
  function planSection(parent, data) {
    const c = planCase(data);
    if (!c.history.displacement || !c.geometry.slab) {
      section(parent, 'Run in plan').appendChild(
        el('p', { text: 'This plan run has no histories or no slab outline (plan/slab_outline) to draw.' }),
      );
      return;
    }
    dampingLine(peaksSection(parent, c), c);
    yieldingSection(parent, c);
    view.animation = planAnimation(section(parent, 'Plan view'), c);
    historySection(parent, c);
    energySection(parent, c);
  }

  Object.assign(kimp, { planSection });
})();
