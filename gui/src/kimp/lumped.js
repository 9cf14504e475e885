// kimp results page: lumped runs (kimp lumped and the building runs of a study): peak tables,
// response charts per case or run, impact pulses, hysteresis loops and the animation.
'use strict';

(function () {
  const { view, el, fmt, column, seriesGroups, chart, section, table, makeAnimation, displayUnit, peakCell } = kimp;

  // ---- lumped runs -----------------------------------------------------------------------------
  /** [factor from SI, unit text] of an SI unit in the reader's display units (kimp.units). */
  const KIND = { m: 'length', 'm/s^2': 'acceleration', N: 'force' };
  const scaleOf = (unit) => (KIND[unit] ? displayUnit(KIND[unit]) : [1, unit]);

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
        const d = h5.datasets[`${base}/deformation_full_rate/value`];
        const at = h5.datasets[`${base}/impact_time`];
        if (v && t && Array.isArray(v.data) && v.data.length) {
          pulses[k.name] = {
            time: t.data,
            force: v.data,
            deformation: d && Array.isArray(d.data) && d.data.length === v.data.length ? d.data : null,
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
        cur = { start: t[i], time: [], force: [], deformation: [] };
        out.push(cur);
      }
      cur.time.push(t[i]);
      cur.force.push(p.force[i]);
      if (p.deformation) cur.deformation.push(p.deformation[i]);
    }
    return out;
  }

  function lumpedSection(parent, data, others) {
    const cases = lumpedCases(data, others && others.length ? data.title : null);
    for (const o of others || []) if (o.h5 && o.h5['lumped.h5']) cases.push(...lumpedCases(o, o.title));
    if (!cases.length) return;
    const first = cases[0];
    const { isolated } = first;

    // Peaks table: the numbers of summary.json, in the display units. The case and the moat
    // walls' peak impact forces (the key result; every contact's when there is no wall) come
    // first and stay pinned while the other columns scroll.
    const body = section(parent, 'Peaks (summary.json)');
    const [L, lengthUnit] = displayUnit('length');
    const [A, accelerationUnit] = displayUnit('acceleration');
    const [F, forceUnit] = displayUnit('force');
    const firstLevel = isolated ? 'peak isolation displacement' : 'peak floor 1 displacement';
    const allContacts = Array.from(new Set(cases.flatMap((c) => c.summary.contacts.map((k) => k.name))));
    const walls = allContacts.filter((n) => /_wall$/.test(n));
    const keyContacts = walls.length ? walls : allContacts.slice(0, 2);
    const contactNames = keyContacts.concat(allContacts.filter((n) => !keyContacts.includes(n)));
    const header = ['case']
      .concat(keyContacts.map((n) => `peak force ${n} (${forceUnit})`))
      .concat([
        'status',
        `${firstLevel} (${lengthUnit})`,
        `peak top displacement (${lengthUnit})`,
        `max interstorey drift (${lengthUnit})`,
        `peak absolute acceleration (${accelerationUnit})`,
        'impacts',
      ])
      .concat(contactNames.slice(keyContacts.length).map((n) => `peak force ${n} (${forceUnit})`));
    const rows = cases.map((c) => {
      const s = c.summary;
      // 4 significant figures on the page; the SI value in full in data-si (and in summary.json).
      const cell = peakCell;
      const top = c.nMain - 1;
      const force = (n) => {
        const k = s.contacts.find((x) => x.name === n);
        return k ? cell(k.peak_force, F, `${s.name}.${n}.peak_force`) : '';
      };
      return [c.label]
        .concat(keyContacts.map(force))
        .concat([
          s.status,
          cell(s.peaks.displacement[0], L, `${s.name}.displacement.0`),
          cell(s.peaks.displacement[top], L, `${s.name}.displacement.${top}`),
          cell(s.max_interstorey_drift, L, `${s.name}.max_interstorey_drift`),
          cell(Math.max(...s.peaks.absolute_acceleration.slice(0, c.nMain)), A, `${s.name}.absolute_acceleration.max`),
          String(s.n_impacts),
        ])
        .concat(contactNames.slice(keyContacts.length).map(force));
    });
    table(body, header, rows, 'data peaks', 1 + keyContacts.length);

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
    const ebody = section(parent, 'Impact events');
    const hostE = el('div');
    ebody.appendChild(hostE);
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
      for (const host of [hostH, hostP, hostE, hostF, hostL, hostI]) host.innerHTML = '';
      view.charts.length = 0;
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
        const [scale, shown] = scaleOf(unit);
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
        const [scale, shown] = scaleOf(unit);
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
      drawEvents(hostE, chosen);
      drawPulses(hostF, chosen);
      drawLoops(hostL, chosen);
      // Isolator hysteresis: its force on the base against the isolation level's displacement.
      const withIsolator = chosen.filter((c) => c.isolated && c.history.isolator_force);
      if (withIsolator.length) {
        const series = withIsolator.map((c) => {
          const f = column(c.history.isolator_force.values, 0);
          const u = column(c.history.displacement.values, 0);
          return { label: c.label, pairs: u.map((d, i) => [d * L, f[i] * F]) };
        });
        const kind = withIsolator[0].summary.isolator ? ` (${withIsolator[0].summary.isolator.kind})` : '';
        scatterChart(
          hostI,
          `isolator hysteresis${kind}`,
          `isolation displacement (${lengthUnit})`,
          `isolator force (${forceUnit})`,
          series,
        );
      }
      if (view.animation) view.animation.setCase(chosen[0]);
    };
    chooser.addEventListener('change', draw);
    const abody = section(parent, 'Animation');
    view.animation = makeAnimation(abody, first);
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
   * One row per impact of the chosen cases, in time order: its time and contact (wall or
   * neighbour floor), peak force and indentation (largest force and deformation of its pulse at
   * full rate, lumped.h5 contacts/<name>/force_full_rate and deformation_full_rate) and closing
   * velocity at first contact (summary.json).
   */
  function drawEvents(host, chosen) {
    const MAX_ROWS = 500;
    const [F, forceUnit] = displayUnit('force');
    const rows = [];
    let sampled = false;
    for (const c of chosen) {
      for (const k of c.summary.contacts || []) {
        const p = c.pulses[k.name];
        const pieces = p ? splitPulses(p) : [];
        // Without the deformation at full rate, the largest indentation of the histories' samples
        // within the pulse (a lower bound at integration.output_interval).
        const hist = c.history.displacement;
        const ind = hist ? indentation(k.name, hist.values, c.resolved, c.nMain) : null;
        const sampledMax = (piece) => {
          let m = null;
          hist.time.forEach((t, i) => {
            if (t >= piece.start && t <= piece.time[piece.time.length - 1] && (m === null || ind[i] > m)) m = ind[i];
          });
          if (m !== null) sampled = true;
          return m;
        };
        (k.impacts || []).forEach((impact) => {
          // The impact's pulse: the first that ends after its time (its force may begin a step
          // after the first contact step).
          const piece = pieces.find((q) => q.time[q.time.length - 1] >= impact.time);
          rows.push({
            c: c,
            contact: k.name,
            time: impact.time,
            velocity: impact.velocity,
            peak: piece ? Math.max(...piece.force) : null,
            indentation: !piece
              ? null
              : piece.deformation.length
                ? Math.max(...piece.deformation)
                : ind
                  ? sampledMax(piece)
                  : null,
          });
        });
      }
    }
    if (!rows.length) {
      host.appendChild(el('p', { class: 'muted', text: 'No impact in the chosen cases.' }));
      return;
    }
    rows.sort((a, b) => a.time - b.time);
    const num = (v, scale, cls) =>
      v === null ? '' : el('span', { class: cls, 'data-si': String(v), text: fmt(v * scale, 4) });
    const multi = chosen.length > 1;
    table(
      host,
      (multi ? ['case'] : []).concat([
        'time (s)',
        'contact',
        `peak force (${forceUnit})`,
        'closing velocity (m/s)',
        sampled ? 'indentation (mm, history samples)' : 'indentation (mm)',
      ]),
      rows
        .slice(0, MAX_ROWS)
        .map((r) =>
          (multi ? [r.c.label] : []).concat([
            num(r.time, 1, 'event-time'),
            r.contact,
            num(r.peak, F, 'event-force'),
            num(r.velocity, 1, 'event-velocity'),
            num(r.indentation, 1e3, 'event-indentation'),
          ]),
        ),
      'data events',
      multi ? 1 : 0,
    );
    if (rows.length > MAX_ROWS)
      host.appendChild(el('p', { class: 'muted', text: `first ${MAX_ROWS} of ${rows.length} impacts` }));
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
            y: piece.force.map((f) => f * displayUnit('force')[0]),
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
        ylabel: `impact force (${displayUnit('force')[1]})`,
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
        const pairs = ind
          .map((d, i) => [d * 1000, f[i] * displayUnit('force')[0]])
          .filter((p, i) => f[i] > 0 || (i > 0 && f[i - 1] > 0));
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
        scatterChart(
          host,
          `force-indentation: ${name}`,
          'indentation (mm)',
          `impact force (${displayUnit('force')[1]})`,
          series,
        );
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

  Object.assign(kimp, { lumpedSection });
})();
