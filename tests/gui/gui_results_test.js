// `kimp gui` in headless Chromium, what an engineer reads: a shipped example opened from the
// examples menu, its model drawn before the run (periods as the run computes them), the peaks
// table at 1280 px with the walls' peak impact forces pinned in view, the impact events table
// against summary.json, display units, the page printed within an A4 width, and the ground
// motion's response spectrum (5 % damping) with the isolated period marked, checked against an
// independent Newmark integration. Screenshots go to ARTEFACT_DIR.
// node gui_results_test.js KIMP ARTEFACT_DIR
'use strict';
const fs = require('fs');
const path = require('path');
const { check, withGuiPage, runMain } = require('./browser.js');

const G = 9.80665;
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

/**
 * Sa(T) = ω² max|u| by Newmark's average acceleration on the record linearly interpolated at
 * `sub` sub-steps per sample (an integration independent of the page's exact recurrence).
 */
function newmarkSa(a, dt, T, zeta, sub) {
  const w = (2 * Math.PI) / T;
  const h = dt / sub;
  const k = w * w;
  const c = 2 * zeta * w;
  const keff = k + (2 * c) / h + 4 / (h * h);
  let u = 0;
  let v = 0;
  let acc = -a[0];
  let peak = 0;
  for (let i = 0; i + 1 < a.length; ++i) {
    for (let j = 1; j <= sub; ++j) {
      const p = -(a[i] + ((a[i + 1] - a[i]) * j) / sub);
      const rhs = p + (4 / (h * h)) * u + (4 / h) * v + acc + c * ((2 / h) * u + v);
      const u1 = rhs / keff;
      const v1 = (2 / h) * (u1 - u) - v;
      acc = (4 / (h * h)) * (u1 - u) - (4 / h) * v - acc;
      u = u1;
      v = v1;
      peak = Math.max(peak, Math.abs(u));
    }
  }
  return k * peak;
}

async function main() {
  const [kimpExe, artefacts] = process.argv.slice(2);
  await withGuiPage(kimpExe, artefacts, { runs: 'gui_results_runs' }, async ({ page, url, runsDir }) => {
    // The examples menu: the shipped scenes, opened with the command that reads them.
    const examples = await page.$$eval('#scene-example option', (os) => os.map((o) => o.value).filter((v) => v));
    const shipped = fs
      .readdirSync(path.join(__dirname, '..', '..', 'data', 'scenes'))
      .filter((f) => f.endsWith('.yaml'))
      .sort();
    check(
      JSON.stringify(examples.slice().sort()) === JSON.stringify(shipped),
      `the examples menu lists data/scenes (${examples.length} scenes)`,
    );
    await page.select('#scene-example', 'isolated_between_neighbours.yaml');
    await page.waitForFunction(() => document.querySelector('#run-name').value === 'isolated_between_neighbours');
    const opened = await page.evaluate(() => ({
      command: document.querySelector('#scene-command').value,
      neighbour: document.querySelector('#scene-form input[data-path="neighbours.left.present"]').checked,
    }));
    check(opened.command === 'lumped' && opened.neighbour, 'the example opens as a lumped scene with its neighbours');

    // The model before the run: drawn, with periods.
    // (The preview follows the form after a short pause: wait for the example's.)
    await page.waitForFunction(() => document.querySelectorAll('#scene-preview svg rect').length > 7, {
      timeout: 10000,
    });
    const facts = await page.$$eval('#scene-preview li', (ls) => ls.map((l) => l.textContent));
    const rects = await page.$$eval('#scene-preview svg rect', (rs) => rs.length);
    const gaps = await page.$$eval('#scene-preview svg .gap-label', (ts) => ts.map((t) => t.textContent));
    check(
      rects === 5 + 4 + 4 + 2 && gaps.join(',') === '15 cm,15 cm',
      `model drawn: ${rects} boxes (isolation level, 4 floors, 2 x 4 neighbour floors, 2 walls), gaps ${gaps}`,
    );
    const preview = await page.evaluate(() =>
      window.kimpGui.postJson('/api/preview', { command: 'lumped', scene: window.kimpGui.sceneYaml() }),
    );
    await page.screenshot({ path: path.join(artefacts, 'gui_preview.png') });

    // Run it: the preview's periods are the run's.
    await page.click('#scene-run');
    await page.waitForSelector('#results .peaks', { timeout: 60000 });
    const runId = await page.$eval('#run-status', (s) => s.textContent.split(':')[0]);
    const summary = JSON.parse(fs.readFileSync(path.join(runsDir, runId, 'out', 'summary.json'), 'utf8'));
    const main0 = preview.buildings[0];
    const runPeriods = summary.cases[0].periods[main0.name];
    check(
      runPeriods.length === main0.periods.length &&
        runPeriods.every((p, i) => Math.abs(p - main0.periods[i]) <= 1e-12 * p),
      `preview periods of ${main0.name} = the run's (${main0.periods.map((p) => p.toFixed(4)).join(', ')} s)`,
    );
    check(
      facts.some((f) => f.includes(`isolated period ${Number(preview.isolated_period.toPrecision(3))} s`)),
      `the isolated period is listed (${preview.isolated_period} s)`,
    );

    // 1280 px: the walls' peak forces in view, pinned while the rest scrolls.
    const kase = summary.cases[0];
    const cellOf = (name) => `#results .peak[data-key="${kase.name}.${name}.peak_force"]`;
    const visible = async (selector) =>
      page.$eval(selector, (e) => {
        const r = e.getBoundingClientRect();
        const w = e.closest('.table-wrap').getBoundingClientRect();
        return r.width > 0 && r.left >= w.left - 1 && r.right <= w.right + 1 && r.right <= window.innerWidth;
      });
    check(
      (await visible(cellOf('left_wall'))) && (await visible(cellOf('right_wall'))),
      'the peak impact forces of both walls are visible at 1280 px',
    );
    const wide = await page.$eval('#results table.peaks', (t) => {
      const w = t.parentElement;
      return { scroll: w.scrollWidth, client: w.clientWidth };
    });
    await page.$eval('#results table.peaks', (t) => {
      t.parentElement.scrollLeft = t.parentElement.scrollWidth;
    });
    await sleep(100);
    check(
      (await visible(cellOf('left_wall'))) && (await visible(cellOf('right_wall'))),
      `scrolled to its last column (table ${wide.scroll} px in ${wide.client} px), the wall forces stay`,
    );
    await page.screenshot({ path: path.join(artefacts, 'gui_results_1280.png') });

    // The impact events table: one row per impact of summary.json, peak force of each contact.
    const events = await page.$$eval('#results table.events tbody tr', (trs) =>
      trs.map((tr) => ({
        time: Number(tr.querySelector('.event-time').dataset.si),
        contact: tr.children[1].textContent,
        force: tr.querySelector('.event-force') ? Number(tr.querySelector('.event-force').dataset.si) : null,
        velocity: Number(tr.querySelector('.event-velocity').dataset.si),
        indentation: tr.querySelector('.event-indentation')
          ? Number(tr.querySelector('.event-indentation').dataset.si)
          : null,
      })),
    );
    const impacts = kase.contacts.flatMap((c) => c.impacts.map((i) => ({ contact: c.name, ...i })));
    check(events.length === impacts.length && impacts.length > 0, `events table: ${events.length} impacts`);
    check(
      impacts.every((i) =>
        events.some((e) => e.contact === i.contact && e.time === i.time && e.velocity === i.velocity),
      ),
      'each impact of summary.json with its time, contact and closing velocity',
    );
    for (const c of kase.contacts.filter((x) => x.impacts.length)) {
      const largest = Math.max(...events.filter((e) => e.contact === c.name).map((e) => e.force));
      check(
        // The page's data are the report's: 7 significant digits.
        Math.abs(largest - c.peak_force) <= 1e-6 * c.peak_force,
        `largest event force of ${c.name} ${largest} N = its peak force in summary.json (${c.peak_force} N)`,
      );
    }
    check(
      events.every((e) => e.indentation === null || e.indentation > 0),
      'indentations are positive where shown',
    );

    // Display units: g and kN.
    const acc = await page.$eval(`#results .peak[data-key="${kase.name}.absolute_acceleration.max"]`, (e) =>
      Number(e.dataset.si),
    );
    await page.select('#results .unit-pick[data-kind="acceleration"]', 'g');
    await page.select('#results .unit-pick[data-kind="force"]', 'kN');
    await page.waitForSelector('#results .unit-pick[data-kind="force"]');
    const shown = await page.evaluate(
      (k) => ({
        acc: document.querySelector(`#results .peak[data-key="${k}.absolute_acceleration.max"]`).textContent,
        force: document.querySelector(`#results .peak[data-key="${k}.left_wall.peak_force"]`).textContent,
        head: Array.from(document.querySelectorAll('#results table.peaks th')).map((t) => t.textContent),
      }),
      kase.name,
    );
    const wall = kase.contacts.find((c) => c.name === 'left_wall').peak_force;
    check(
      Number(shown.acc) === Number((acc / G).toPrecision(4)) &&
        Number(shown.force) === Number((wall / 1e3).toPrecision(4)),
      `units g and kN: acceleration ${shown.acc} g, left wall ${shown.force} kN`,
    );
    check(
      shown.head.includes('peak absolute acceleration (g)') && shown.head.includes('peak force left_wall (kN)'),
      'the headers name the chosen units',
    );
    await page.select('#results .unit-pick[data-kind="acceleration"]', 'm/s²');
    await page.select('#results .unit-pick[data-kind="force"]', 'MN');

    // Print: nothing wider than an A4 page's text (210 mm - 2 x 10 mm margins = 718 CSS px).
    await page.emulateMediaType('print');
    await page.setViewport({ width: 718, height: 1000 });
    await page.evaluate(() => window.dispatchEvent(new Event('beforeprint')));
    const overflowing = () => {
      const out = [];
      for (const e of document.querySelectorAll('#results .card, #results table, #results svg, #results canvas')) {
        const r = e.getBoundingClientRect();
        if (r.width === 0) continue;
        if (r.right > 718 + 1) out.push(`${e.tagName}.${e.className} right ${Math.round(r.right)}`);
      }
      for (const w of document.querySelectorAll('#results .table-wrap'))
        if (w.scrollWidth > w.clientWidth + 1) out.push(`table ${w.scrollWidth} px in ${w.clientWidth} px`);
      return out;
    };
    // The charts follow their cards' width once laid out (a resize observer): give them 5 s.
    await page.waitForFunction(`(${overflowing.toString()})().length === 0`, { timeout: 5000 }).catch(() => {});
    const overflow = await page.evaluate(overflowing);
    check(overflow.length === 0, `print layout within A4 width (${overflow.slice(0, 5).join('; ') || 'no overflow'})`);
    await page.pdf({ path: path.join(artefacts, 'gui_results_print.pdf'), format: 'A4', printBackground: true });
    await page.evaluate(() => window.dispatchEvent(new Event('afterprint')));
    await page.emulateMediaType('screen');
    await page.setViewport({ width: 1280, height: 900 });

    // The response spectrum of the scene's motion, the isolated period marked.
    await page.click('header.top nav button[data-tab="motion"]');
    await page.waitForSelector('#motion-charts .spectrum-host[data-isolated-period]', { timeout: 20000 });
    const spec = await page.$eval('#motion-charts .spectrum-host', (h) => ({
      T: Number(h.dataset.isolatedPeriod),
      sa: Number(h.dataset.saAtPeriod),
      title: h.querySelector('.chart-title').textContent,
    }));
    check(
      Math.abs(spec.T - preview.isolated_period) <= 1e-12 * spec.T,
      `the spectrum marks the isolated period ${spec.T} s`,
    );
    const scene = await page.evaluate(() => window.kimpGui.sceneYaml());
    const motion = await (
      await fetch(url + 'api/motion', {
        method: 'POST',
        headers: { 'Content-Type': 'application/json', 'X-Kimp-Request': '1' },
        body: JSON.stringify({ command: 'lumped', scene: scene }),
      })
    ).json();
    const reference = newmarkSa(motion.acceleration, motion.dt, spec.T, 0.05, 20);
    check(
      Math.abs(spec.sa - reference) <= 0.005 * reference,
      `Sa(T_iso) on the page ${(spec.sa / G).toFixed(4)} g = Newmark ${(reference / G).toFixed(4)} g (0.5 %)`,
    );
    const series = await page.evaluate(() => {
      const c = window.kimp.charts().find((x) => x.card.classList.contains('spectrum'));
      return c.plot.series.slice(1).map((s) => s.label);
    });
    check(series.some((s) => /^isolated period/.test(s)), `period marker on the spectrum: ${series.join(' | ')}`);
    await page.$eval('#motion-charts .spectrum-host', (h) => h.scrollIntoView());
    await page.screenshot({ path: path.join(artefacts, 'gui_spectrum.png') });
  });
}

runMain(main);
