// `kimp report DIR` opens from file:// in headless Chromium: no network request, no console
// error, the charts and the animation are there, and a chart exports as SVG.
// node report_test.js KIMP RESULT_DIR ARTEFACT_DIR
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');
const { launch, watchedPage, waitForFile, check } = require('./browser.js');

async function main() {
  const [kimpExe, dir, artefacts] = process.argv.slice(2);
  fs.mkdirSync(artefacts, { recursive: true });
  const html = path.join(artefacts, path.basename(dir) + '_report.html');
  execFileSync(kimpExe, ['-q', 'report', dir, '-o', html]);
  const browser = await launch();
  try {
    const downloads = path.join(artefacts, 'downloads_' + path.basename(dir));
    const { page, log } = await watchedPage(browser, downloads);
    await page.goto('file://' + html, { waitUntil: 'load' });
    await page.waitForSelector('.chart canvas');
    const nCharts = await page.$$eval('.chart', (cs) => cs.length);
    check(nCharts > 0, `${nCharts} charts drawn`);
    const foreign = log.requests.filter(
      (u) => !u.startsWith('file://') && !u.startsWith('blob:') && !u.startsWith('data:'),
    );
    check(foreign.length === 0, `no network request (${foreign.join(' ') || 'none'})`);
    await page.screenshot({ path: path.join(artefacts, path.basename(dir) + '_report.png'), fullPage: false });
    // Export the first chart as SVG and check that it is a drawing of the chart.
    await page.$eval('.chart .export-svg', (b) => b.click());
    const title = await page.$eval('.chart .chart-title', (t) => t.textContent);
    const name = title.replace(/[^A-Za-z0-9_.-]+/g, '_').replace(/^_+|_+$/g, '') + '.svg';
    const svg = await waitForFile(path.join(downloads, name), 5000);
    check(svg.startsWith('<svg') && svg.includes('<path d="M'), `exported ${name} holds the series as SVG paths`);
    // The same chart as PDF: a vector page written by gui/src/kimp/charts.js (paths and Helvetica text).
    await page.$eval('.chart .export-pdf', (b) => b.click());
    const pdf = await waitForFile(path.join(downloads, name.replace(/\.svg$/, '.pdf')), 5000);
    check(
      pdf.startsWith('%PDF-1.4') && pdf.includes(' l\n') && pdf.trimEnd().endsWith('%%EOF'),
      `exported ${name.replace(/\.svg$/, '.pdf')} is a vector PDF`,
    );
    // A lumped run with an isolator shows its hysteresis loop (force against the isolation
    // displacement) whose largest force is the summary's peak within the history sampling.
    const summary = JSON.parse(fs.readFileSync(path.join(dir, 'summary.json'), 'utf8'));
    const withIsolator = (summary.cases || []).find((c) => c.isolator && c.status === 'ok');
    if (withIsolator) {
      const loop = await page.evaluate(() => {
        const c = window.kimp.charts().find((x) => x.title.startsWith('isolator hysteresis'));
        if (!c) return null;
        const ys = Array.from(c.plot.data[1]).filter((v) => v !== null && v !== undefined);
        return { n: ys.length, max: Math.max(...ys.map(Math.abs)) };
      });
      check(loop !== null && loop.n > 10, `isolator hysteresis loop drawn (${loop ? loop.n : 0} points)`);
      const peak = withIsolator.isolator.peak_force * 1e-6;
      check(
        loop.max <= peak * (1 + 1e-9) && loop.max > 0.5 * peak,
        `loop's largest force ${loop.max.toFixed(4)} MN within the peak ${peak.toFixed(4)} MN`,
      );
    }
    if (await page.$('svg.animation')) {
      await page.$eval('.anim-play', (b) => b.click());
      await new Promise((r) => setTimeout(r, 600));
      const t = await page.evaluate(() => window.kimp.animation().state.t);
      check(t > 0, `animation plays from file:// (t = ${t})`);
    }
    // Impact pulses at full rate (force_full_rate): the largest force drawn of a contact is its
    // peak force of summary.json (7 significant digits in the report).
    const hit = (summary.cases || []).flatMap((c) =>
      (c.contacts || []).filter((k) => k.impacts && k.impacts.length).map((k) => [c, k]),
    );
    if (hit.length) {
      const [c, k] = hit[0];
      const drawn = await page.evaluate((name) => {
        const ch = window.kimp.charts().find((x) => x.title === `impact force pulses at full rate: ${name}`);
        if (!ch) return null;
        let m = 0;
        for (const ys of ch.plot.data.slice(1))
          for (const y of ys) if (y !== null && y !== undefined) m = Math.max(m, y);
        return { max: m, n: ch.plot.data[0].length };
      }, k.name);
      check(drawn !== null && drawn.n > 50, `${k.name}: pulses drawn at full rate (${drawn ? drawn.n : 0} samples)`);
      const peak = k.peak_force * 1e-6;
      check(
        Math.abs(drawn.max - peak) <= 1e-6 * peak,
        `${c.name} ${k.name}: largest pulse force ${drawn.max} MN = peak force ${peak} MN (1e-6)`,
      );
    }
    if (summary.command === 'study') {
      // k(H): one chart per law, one series per impact velocity (plus the thesis), y in its unit.
      const kh = await page.evaluate(() =>
        window.kimp
          .charts()
          .filter((x) => / k\(H\)/.test(x.title))
          .map((x) => ({ y: x.ylabel, labels: x.plot.series.slice(1).map((s) => s.label) })),
      );
      check(
        kh.length === 2 && kh[0].y === 'k (kN/mm/m)' && kh[1].y === 'k (kN/mm^1.5/m)',
        `k(H) charts per law with their units (${kh.map((x) => x.y).join(', ')})`,
      );
      const rows = fs.readFileSync(path.join(dir, 'k_table.csv'), 'utf8').trim().split('\n');
      // The answer first: the page's first section is k at the reference velocity, one row per
      // height with the fit/FEM peak ratio; k_table.csv lists the reference rows first.
      const rcol = rows[0].split(',').indexOf('reference_velocity');
      const nReference = rows.slice(1).filter((r) => r.split(',')[rcol] === 'yes').length;
      check(rcol >= 0 && rows[1].split(',')[rcol] === 'yes', `k_table.csv begins with a reference row`);
      // The yielding walls come first (one row per building run with a wall, as in
      // yielding_wall.csv), then the k table as the comparison with Table 2.1: with inelastic
      // materials the walls of every run; in a linear study the estimate element run beside the
      // impact springs, titled so, every row's element from the estimate.
      const yieldingCsv = path.join(dir, 'yielding_wall.csv');
      const yielding = fs.existsSync(yieldingCsv);
      if (yielding) {
        const runs = fs.readFileSync(yieldingCsv, 'utf8').trim().split('\n');
        const linear = summary.yielding_wall && summary.yielding_wall.route === 'linear';
        const head = runs[0].split(',');
        const residualCsv = runs
          .slice(1)
          .map((r) => r.split(',')[head.indexOf('residual_wall_displacement_cm')]);
        const shown = await page.evaluate(() => {
          const first = document.querySelector('details.section');
          const t = first && first.querySelector('table.yielding-answer');
          const column = (name) => {
            if (!t) return [];
            const i = Array.from(t.querySelectorAll('th')).findIndex((h) => h.textContent === name);
            return Array.from(t.querySelectorAll('tbody tr')).map((r) => (i < 0 ? null : r.children[i].textContent));
          };
          return {
            title: first ? first.querySelector('summary').textContent : '',
            rows: column('element from'),
            envelopes: column('envelope'),
            capacity: column('capacity (kN/m)'),
            residual: column('residual (cm)'),
          };
        });
        check(
          (linear
            ? shown.title.startsWith('Moat walls as yielding elements (estimate, beside the linear springs)') &&
              shown.rows.every((s) => s === 'estimate')
            : shown.title.startsWith('Yielding moat walls') &&
              shown.rows.every((s) => s === 'pushover' || s === 'estimate')) &&
            shown.rows.length === runs.length - 1 &&
            shown.envelopes.every((s) => s === 'hull' || s === 'bilinear'),
          `the first section is the yielding walls (${shown.title}, ${shown.rows.length} of ` +
            `${runs.length - 1} runs, element from ${shown.rows.join(', ')}, envelope ` +
            `${shown.envelopes.join(', ')})`,
        );
        // Each row shows its capacity per metre and its residual displacement, as in the CSV.
        check(
          shown.capacity.length === runs.length - 1 &&
            shown.capacity.every((c) => c !== null && Number(c) > 0) &&
            shown.residual.every((c, i) => {
              const expected = Number(residualCsv[i]);
              return c !== null && Math.abs(Number(c) - expected) <= 1e-3 * Math.abs(expected) + 1e-9;
            }),
          `capacity (kN/m) ${shown.capacity.join(', ')} and residual (cm) ${shown.residual.join(', ')} ` +
            `as in yielding_wall.csv (${residualCsv.join(', ')})`,
        );
      }
      const answer = await page.evaluate((second) => {
        const first = document.querySelectorAll('details.section')[second ? 1 : 0];
        const t = first && first.querySelector('table.k-answer');
        return {
          title: first ? first.querySelector('summary').textContent : '',
          rows: t ? t.querySelectorAll('tbody tr').length : 0,
          head: t ? Array.from(t.querySelectorAll('th')).map((h) => h.textContent) : [],
        };
      }, yielding);
      check(
        answer.title.startsWith('Impact stiffness k (the answer') && answer.rows === nReference &&
          answer.head.includes('KV fit/FEM peak'),
        `the first section is the reference k table (${answer.title}, ${answer.rows} of ${nReference} rows)`,
      );
      const vcol = rows[0].split(',').indexOf('impact_velocity_m_per_s');
      const nv = new Set(rows.slice(1).map((r) => r.split(',')[vcol])).size;
      check(
        kh[0].labels.filter((l) => l.startsWith('v = ')).length >= nv,
        `one series per impact velocity (${nv}): ${kh[0].labels.join(' | ')}`,
      );
    }
    if (summary.command === 'fit' || fs.existsSync(path.join(dir, 'fit.h5'))) {
      const fit = await page.evaluate(() =>
        window.kimp
          .charts()
          .filter((x) => x.title.endsWith('FEM contact force and the fitted laws'))
          .map((x) => x.plot.series.slice(1).map((s) => s.label)),
      );
      check(
        fit.length > 0 && fit[0][0] === 'FEM' && fit[0].length > 1,
        `FEM force with the fitted laws: ${fit[0].join(' | ')}`,
      );
      const ks = await page.$$eval('table.fit-table .fit-k', (es) => es.map((e) => e.textContent));
      check(ks.length > 0 && ks.every((t) => /kN\/mm(\^[\d.]+)?\/m$/.test(t)), `k table with units: ${ks.join(', ')}`);
    }
    if (summary.command === 'fem') {
      // The FEM summary table: every case's peak force and COR as in summary.json, in kN/m and
      // to 4 significant figures (the file keeps full precision).
      const shown = await page.$$eval('table.fem-summary .fem-summary-value', (vs) =>
        vs.map((v) => ({
          key: v.getAttribute('data-key'),
          si: Number(v.getAttribute('data-si')),
          text: v.textContent,
        })),
      );
      for (const c of summary.cases) {
        const peak = shown.find((v) => v.key === `${c.name}.peak_force`);
        check(
          peak !== undefined &&
            peak.si === c.peak_force &&
            peak.text === String(Number((c.peak_force * 1e-3).toPrecision(4))),
          `FEM summary: ${c.name} peak force ${peak ? peak.text : '(missing)'} kN/m from ${c.peak_force} N/m`,
        );
        // Where the energy went: every dissipation the case reports is listed, to 4 significant
        // figures (the slab's damping and the far side's dashpots and springs in the damped-slab
        // run).
        for (const key of [
          'contact_dissipation',
          'radiated_energy',
          'slab_damping_dissipation',
          'boundary_spring_energy',
        ]) {
          if (typeof c[key] !== 'number') continue;
          const v = shown.find((x) => x.key === `${c.name}.${key}`);
          check(
            v !== undefined && v.si === c[key] && v.text === String(Number(c[key].toPrecision(4))),
            `FEM summary: ${c.name} ${key} ${v ? v.text : '(missing)'} J/m from ${c[key]} J/m`,
          );
        }
        const cor = shown.find((v) => v.key === `${c.name}.apparent_cor`);
        check(
          cor !== undefined && cor.text.replace('-', '').replace('.', '').replace(/^0+/, '').length <= 4,
          `FEM summary: ${c.name} COR shown to 4 significant figures (${cor ? cor.text : '(missing)'})`,
        );
      }
    }
    if (await page.$('svg.fem-animation')) {
      // The FEM deformed mesh: one polygon per cell, frames advance on play and hold on pause.
      const nPoly = await page.$$eval('svg.fem-animation polygon', (ps) => ps.length);
      const nCells = await page.evaluate(() => window.kimp.femAnimation().state.mesh.cells.length);
      check(nPoly === nCells && nCells > 0, `deformed mesh drawn: ${nPoly} polygons for ${nCells} cells`);
      await page.$eval('.fem-play', (b) => b.click());
      await new Promise((r) => setTimeout(r, 700));
      const f1 = await page.evaluate(() => window.kimp.femAnimation().state.frame);
      check(f1 > 0, `FEM animation advances (frame ${f1})`);
      await page.$eval('.fem-play', (b) => b.click());
      const held = await page.evaluate(() => window.kimp.femAnimation().state.frame);
      await new Promise((r) => setTimeout(r, 400));
      const f2 = await page.evaluate(() => window.kimp.femAnimation().state.frame);
      check(f2 === held, `pause holds the frame (${held} -> ${f2})`);
      // A click on the force history moves the mesh to the frame nearest that time.
      const target = await page.evaluate(() => {
        const c = window.kimp.charts().find((x) => x.title.endsWith(': contact force'));
        const ts = window.kimp.femAnimation().state.mesh.time;
        const t = ts[Math.floor(ts.length / 2)];
        c.plot.over.scrollIntoView();
        const r = c.plot.over.getBoundingClientRect();
        return { x: r.x + c.plot.valToPos(t, 'x'), y: r.y + r.height / 2, t: t };
      });
      await page.mouse.click(target.x, target.y);
      const clicked = await page.evaluate(() => window.kimp.femAnimation().time());
      const dtFrame = await page.evaluate(() => {
        const ts = window.kimp.femAnimation().state.mesh.time;
        return ts[1] - ts[0];
      });
      check(
        Math.abs(clicked - target.t) <= dtFrame,
        `clicking the force history at ${target.t} s shows the frame at ${clicked} s`,
      );
      const scrubWidth = await page.$eval('.fem-scrub', (x) => x.getBoundingClientRect().width);
      check(scrubWidth > 600, `the FEM scrub slider spans the animation (${scrubWidth} px)`);
      const fields = await page.$$eval('.fem-field option', (os) => os.map((o) => o.value));
      check(
        fields.includes('von_mises_stress') && fields.includes('mean_stress'),
        `fields to colour by: ${fields.join(', ')}`,
      );
      await page.$eval('svg.fem-animation', (s) => s.scrollIntoView());
      await page.screenshot({ path: path.join(artefacts, path.basename(dir) + '_fem_mesh.png') });
      if (fields.includes('contact_pressure')) {
        // Contact pressure at the frame of the largest contact force: the contact face drawn in
        // the pressure's colours over a neutral mesh, other colours than the stress field's.
        const peak = await page.evaluate(() => {
          const a = window.kimp.femAnimation();
          const { values: rows, length: len } = a.state.mesh.fields.contact_pressure;
          const force = rows.map((r) => r.reduce((s, p, k) => s + p * len[k], 0));
          const i = force.indexOf(Math.max(...force));
          a.seek(i);
          return { frame: i, force: force[i] };
        });
        check(
          peak.force > 0,
          `frame ${peak.frame} has the largest integrated contact pressure (${(peak.force * 1e-3).toFixed(1)} kN/m)`,
        );
        // Frames are denser around the force peak: the frame nearest the peak of the contact
        // force history is within 0.15 ms of it and carries at least 90 % of its force.
        const nearest = await page.evaluate(() => {
          const d = JSON.parse(document.getElementById('kimp-data').textContent).h5['fem.h5'].datasets;
          const key = Object.keys(d).find((k) => /^\/fem\/[^/]+\/contact_force\/value$/.test(k));
          const f = d[key].data;
          const t = d[key.replace(/value$/, 'time')].data;
          const k = f.indexOf(Math.max(...f));
          const a = window.kimp.femAnimation();
          const ts = a.state.mesh.time;
          let i = 0;
          for (let j = 1; j < ts.length; ++j) if (Math.abs(ts[j] - t[k]) < Math.abs(ts[i] - t[k])) i = j;
          const { values: rows, length: len } = a.state.mesh.fields.contact_pressure;
          const fFrame = rows[i].reduce((s, p, m) => s + p * len[m], 0);
          return { tPeak: t[k], fPeak: f[k], tFrame: ts[i], fFrame: fFrame };
        });
        check(
          Math.abs(nearest.tFrame - nearest.tPeak) <= 1.5e-4 && nearest.fFrame >= 0.9 * nearest.fPeak,
          `frame at ${(nearest.tFrame * 1e3).toFixed(3)} ms near the force peak at ` +
            `${(nearest.tPeak * 1e3).toFixed(3)} ms: ${(nearest.fFrame * 1e-3).toFixed(1)} of ` +
            `${(nearest.fPeak * 1e-3).toFixed(1)} kN/m`,
        );
        const colours = () =>
          page.$$eval('svg.fem-animation polygon, svg.fem-animation polyline', (ps) =>
            ps.map((p) => p.getAttribute('fill') + '/' + p.getAttribute('stroke')).join(';'),
          );
        const before = await colours();
        await page.select('.fem-field', 'contact_pressure');
        const after = await colours();
        check(after !== before, 'choosing contact pressure changes the drawn colours');
        const face = await page.$$eval('svg.fem-animation polyline.contact-face', (ls) =>
          ls.map((l) => l.getAttribute('stroke')),
        );
        const nodes = await page.evaluate(
          () => window.kimp.femAnimation().state.mesh.fields.contact_pressure.nodes.length,
        );
        check(
          face.length === nodes && new Set(face).size > 1,
          `contact face drawn: ${face.length} pieces for ${nodes} nodes, ${new Set(face).size} colours`,
        );
        const neutral = await page.$$eval(
          'svg.fem-animation polygon',
          (ps) => ps.filter((p) => p.getAttribute('fill') === '#d9d9d9').length,
        );
        check(neutral > 0.5 * nCells, `the rest of the mesh neutral (${neutral} of ${nCells} cells)`);
        const bar = await page.$eval('svg.fem-animation', (s) => s.textContent);
        check(/contact pressure \((kPa|MPa)\)/.test(bar), 'colour bar in kPa or MPa');
        await page.screenshot({ path: path.join(artefacts, path.basename(dir) + '_fem_pressure.png') });
      }
    }
    check(log.errors.length === 0, `no console error (${log.errors.join(' | ') || 'none'})`);
  } finally {
    await browser.close();
  }
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
