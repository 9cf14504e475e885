// `kimp gui` in headless Chromium, the editor and ground-motion tabs and the overlay of runs:
// an imported scene with a block scalar and a misspelt key (reported at its section, as the CLI
// refuses it), an error inside a list flagged at the list's box, a two-column record uploaded
// with its unit, scaled and trimmed on the page exactly as the run then scales it, and two runs
// overlaid on one chart. Screenshots go to ARTEFACT_DIR.
// node gui_editor_test.js KIMP ARTEFACT_DIR
'use strict';
const fs = require('fs');
const path = require('path');
const { check, setMotionInputs, setField, withGuiPage, runMain } = require('./browser.js');

const G = 9.80665;

async function main() {
  const [kimpExe, artefacts] = process.argv.slice(2);
  await withGuiPage(kimpExe, artefacts, { runs: 'gui_editor_runs' }, async ({ page, runsDir }) => {

    // Import: js-yaml reads the folded block scalar; the misspelt key is reported at walls.left.
    const scene = path.join(artefacts, 'imported_scene.yaml');
    fs.writeFileSync(
      scene,
      '# a scene with a typo\nbuilding:\n  n_storeys: 3\nwalls:\n  left:\n    gapz: "10 cm"\n' +
        'ground_motion:\n  record: >-\n    synthetic\n  duration: "6 s"\n',
    );
    await (await page.$('#scene-import')).uploadFile(scene);
    await page.waitForSelector('details.error[data-path="walls.left"] > .field-error');
    const note = await page.$eval('details.error[data-path="walls.left"] > .field-error', (e) => e.textContent);
    check(
      /unknown key 'gapz' in walls\.left \(known: .*\bgap\b/.test(note),
      `unknown key reported at its section: ${note}`,
    );
    const record = await page.$eval('#scene-form input[data-path="ground_motion.record"]', (i) => i.value);
    check(record === 'synthetic', `block scalar read by js-yaml (record = "${record}")`);
    // Kept in the YAML, so the server refuses it with the CLI's own message.
    await page.click('#scene-validate');
    await page.waitForFunction(() => /unknown key 'gapz'/.test(document.querySelector('#scene-error').textContent));
    check(true, 'Validate refuses the unknown key as the CLI does');

    // An error inside a list: cases[0].law flagged at the cases box.
    await page.$eval('#scene-yaml', (t) => {
      t.value = 'building:\n  n_storeys: 3\ncases:\n  - name: a\n    law: kelvin_voigtt\n';
    });
    await page.$eval('#scene-apply', (b) => b.click());
    await page.click('#scene-validate');
    await page.waitForSelector('.field.error[data-path="cases"] .field-error');
    const listError = await page.$eval('.field.error[data-path="cases"] .field-error', (e) => e.textContent);
    check(/cases\[0\]\.law\b.*kelvin_voigtt/.test(listError), `list error at the cases box: ${listError}`);
    await page.screenshot({ path: path.join(artefacts, 'gui_list_error.png') });

    // A first run: the small scene with the synthetic motion.
    await page.$eval('#scene-yaml', (t) => {
      t.value =
        'building:\n  n_storeys: 3\nwalls:\n  left:\n    gap: "8 cm"\n  right:\n    gap: "8 cm"\n' +
        'ground_motion:\n  duration: "6 s"\n';
    });
    await page.$eval('#scene-apply', (b) => b.click());
    await page.click('#scene-run');
    await page.waitForSelector('#results .peaks', { timeout: 60000 });
    const firstRun = await page.$eval('#run-status', (s) => s.textContent.split(':')[0]);

    // Ground motion: a two-column record in g (0.3 g sine, dt 0.01 s, 10 s) uploaded.
    const lines = [];
    for (let i = 0; i <= 1000; ++i)
      lines.push(`${(i * 0.01).toFixed(2)} ${(0.3 * Math.sin(2 * Math.PI * 1.3 * i * 0.01)).toFixed(6)}`);
    const record2 = path.join(artefacts, 'sine_g.txt');
    fs.writeFileSync(record2, lines.join('\n') + '\n');
    await page.click('header.top nav button[data-tab="motion"]');
    await page.select('#motion-unit', 'g');
    await (await page.$('#motion-upload')).uploadFile(record2);
    // The upload's plot (not the synthetic motion the tab opened with).
    await page.waitForFunction(() => /^sine_g\b/.test(document.querySelector('#motion-info').textContent));
    const pga0 = await page.$eval('#motion-info', (e) => Number(e.dataset.pga));
    const peak = Math.max(...lines.map((l) => Math.abs(Number(l.split(' ')[1]))));
    check(Math.abs(pga0 - peak) < 1e-9, `PGA of the upload ${pga0} g = largest sample ${peak} g`);
    const nCharts = await page.$$eval('#motion-charts > .chart', (c) => c.length);
    check(nCharts === 3, `acceleration, velocity and displacement drawn (${nCharts} charts)`);
    // Scale 0.5 and a duration in ms: the page shows what the run will use (the answer to the last
    // change: the page draws only the latest answer of the server).
    await setMotionInputs(page, [['#motion-scale', '0.5'], ['#motion-duration', '5000 ms']], 500);
    const pga = await page.$eval('#motion-info', (e) => Number(e.dataset.pga));
    const samples = await page.$eval('#motion-info', (e) => Number(e.dataset.samples));
    check(Math.abs(pga - 0.5 * pga0) < 1e-12, `scale 0.5 halves the PGA shown (${pga0} -> ${pga} g)`);
    check(samples === 500, `duration "5000 ms" keeps 5 s = ${samples} samples`);
    const title = await page.$eval('#motion-charts > .chart .chart-title', (e) => e.textContent);
    check(title.includes(`PGA = ${Number(pga.toPrecision(4))} g`), `PGA on the acceleration chart: ${title}`);
    await page.screenshot({ path: path.join(artefacts, 'gui_motion.png') });
    const yaml = await page.$eval('#scene-yaml', (t) => t.value);
    check(
      /record_unit: "g"/.test(yaml) && /record: ".*sine_g\.txt"/.test(yaml),
      'the upload sets record and record_unit',
    );

    // Run on the upload: the run scales and trims the record as the page showed.
    await page.click('header.top nav button[data-tab="scene"]');
    await setField(page, 'building.n_storeys', '3');
    await page.click('#scene-run');
    await page.waitForFunction(
      (prev) => {
        const s = document.querySelector('#run-status');
        return (
          s &&
          !s.textContent.startsWith(prev) &&
          s.dataset.state === 'done' &&
          document.querySelector('#results .peaks')
        );
      },
      { timeout: 60000 },
      firstRun,
    );
    const secondRun = await page.$eval('#run-status', (s) => s.textContent.split(':')[0]);
    const summary = JSON.parse(fs.readFileSync(path.join(runsDir, secondRun, 'out', 'summary.json'), 'utf8'));
    check(
      Math.abs(summary.ground_motion.pga - pga * G) <= 1e-9 * pga * G,
      `run's PGA ${summary.ground_motion.pga} m/s² = page's ${pga} g`,
    );
    check(
      Math.abs(summary.ground_motion.duration - 5) < 1e-9,
      `run's record is 5 s long (${summary.ground_motion.duration} s)`,
    );

    // Overlay: the first run's histories on the second run's charts, legend "run: case".
    await page.waitForSelector('.overlay-run');
    await page.$$eval(
      '.overlay-run',
      (bs, id) =>
        bs.forEach((b) => {
          b.checked = b.value === id;
        }),
      firstRun,
    );
    await page.click('.overlay-apply');
    await page.waitForFunction(() => document.querySelectorAll('#results .case-box').length === 2);
    const series = await page.evaluate(() => {
      const c = window.kimp.charts()[0];
      return { labels: c.plot.series.slice(1).map((s) => s.label), n: c.plot.data.length };
    });
    check(
      series.labels.length === 2 &&
        series.labels[0] === `${secondRun}: default` &&
        series.labels[1] === `${firstRun}: default`,
      `two runs on one chart: ${series.labels.join(' | ')}`,
    );
    await page.screenshot({ path: path.join(artefacts, 'gui_overlay.png') });
  });
}

runMain(main);
