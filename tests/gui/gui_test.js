// `kimp gui` in headless Chromium: edit a small lumped scene through the form, see a bad value
// flagged at its field, run, compare the peaks on the page with summary.json, play and pause the
// animation, export a chart as SVG; no console error. Screenshots go to ARTEFACT_DIR.
// node gui_test.js KIMP ARTEFACT_DIR
'use strict';
const fs = require('fs');
const path = require('path');
const { waitForFile, check, setField, withGuiPage, runMain } = require('./browser.js');

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function main() {
  const [kimpExe, artefacts] = process.argv.slice(2);
  const where = { runs: 'gui_runs', downloads: 'downloads_gui' };
  await withGuiPage(kimpExe, artefacts, where, async ({ page, runsDir, downloadDir: downloads }) => {
    const nFields = await page.$$eval('#scene-form .field', (f) => f.length);
    check(nFields > 40, `editor form generated from the schema (${nFields} fields)`);

    // A value out of range is flagged at its field with the CLI's own message.
    await setField(page, 'building.n_storeys', '0');
    await page.click('#scene-validate');
    await page.waitForSelector('.field.error[data-path="building.n_storeys"] .field-error');
    const message = await page.$eval('.field.error .field-error', (e) => e.textContent);
    check(/scene\.yaml:\d+: building\.n_storeys\b.*\b0\b/.test(message), `error at the field: "${message}"`);
    await page.screenshot({ path: path.join(artefacts, 'gui_field_error.png') });

    // The small scene, set through the form.
    await setField(page, 'building.n_storeys', '3');
    await setField(page, 'walls.left.gap', '8 cm');
    await setField(page, 'walls.right.gap', '8 cm');
    await setField(page, 'ground_motion.duration', '6 s');
    const yaml = await page.$eval('#scene-yaml', (t) => t.value);
    check(yaml.includes('n_storeys: 3') && yaml.includes('gap: "8 cm"'), 'the form writes the YAML scene');
    // The model preview follows the form (after a short pause).
    await page.waitForFunction(() => /\b3 storeys\b/.test(document.querySelector('#scene-preview').textContent));
    await page.screenshot({ path: path.join(artefacts, 'gui_editor.png') });
    await page.click('#scene-run');
    await page.waitForSelector('#results .peaks', { timeout: 60000 });
    const runId = await page.$eval('#run-status', (s) => s.textContent.split(':')[0]);
    const summary = JSON.parse(fs.readFileSync(path.join(runsDir, runId, 'out', 'summary.json'), 'utf8'));
    const peaks = await page.$$eval('#results .peak', (ps) =>
      ps.map((p) => ({ key: p.dataset.key, text: p.textContent, scale: Number(p.dataset.scale) })),
    );
    const kase = summary.cases[0];
    const expected = {
      [`${kase.name}.displacement.0`]: kase.peaks.displacement[0],
      [`${kase.name}.displacement.3`]: kase.peaks.displacement[3],
      [`${kase.name}.max_interstorey_drift`]: kase.max_interstorey_drift,
      [`${kase.name}.left_wall.peak_force`]: kase.contacts.find((c) => c.name === 'left_wall').peak_force,
      [`${kase.name}.right_wall.peak_force`]: kase.contacts.find((c) => c.name === 'right_wall').peak_force,
    };
    for (const [key, value] of Object.entries(expected)) {
      const shown = peaks.find((p) => p.key === key);
      check(
        shown && Number(shown.text) === Number((value * shown.scale).toPrecision(4)),
        `peak ${key} on the page (${shown && shown.text}) equals summary.json (${value})`,
      );
    }
    check(kase.n_impacts > 0, `the run pounds the walls (${kase.n_impacts} impacts)`);
    await page.screenshot({ path: path.join(artefacts, 'gui_results.png') });

    // Animation: frames advance while playing, pause holds.
    await page.$eval('svg.animation', (s) => s.scrollIntoView());
    await page.click('.anim-play');
    await sleep(700);
    const t1 = await page.evaluate(() => window.kimp.animation().state.t);
    const f1 = await page.evaluate(() => window.kimp.animation().state.frame);
    await sleep(500);
    const t2 = await page.evaluate(() => window.kimp.animation().state.t);
    const f2 = await page.evaluate(() => window.kimp.animation().state.frame);
    check(
      t2 > t1 && f2 > f1,
      `frames advance while playing (frame ${f1} -> ${f2}, t ${t1.toFixed(2)} -> ${t2.toFixed(2)} s)`,
    );
    await page.click('.anim-play');
    const p1 = await page.evaluate(() => window.kimp.animation().state.t);
    await sleep(500);
    const p2 = await page.evaluate(() => window.kimp.animation().state.t);
    check(p1 === p2, `pause holds (t = ${p1.toFixed(3)} s)`);
    // Jump to the first impact and look at it.
    const tImpact = kase.contacts.find((c) => c.impacts.length).impacts[0].time;
    await page.evaluate((t) => window.kimp.animation().seek(t + 0.005), tImpact);
    await page.$eval('svg.animation', (s) => s.scrollIntoView());
    await page.screenshot({ path: path.join(artefacts, 'gui_animation.png') });

    // Export the displacement chart as SVG.
    await page.$eval('#results .chart .export-svg', (b) => b.click());
    const title = await page.$eval('#results .chart .chart-title', (t) => t.textContent);
    const file = path.join(downloads, title.replace(/[^A-Za-z0-9_.-]+/g, '_').replace(/^_+|_+$/g, '') + '.svg');
    const svg = await waitForFile(file, 5000);
    check(
      svg.startsWith('<svg') && svg.includes('<path d="M') && svg.includes('time (s)'),
      `chart exported as SVG (${path.basename(file)}, ${svg.length} bytes)`,
    );
    fs.copyFileSync(file, path.join(artefacts, 'gui_chart.svg'));
    // ... and its data as CSV: the header names each column with its unit.
    await page.$eval('#results .chart .export-csv', (b) => b.click());
    const csvText = await waitForFile(file.replace(/\.svg$/, '.csv'), 5000);
    const csvHead = csvText.split('\n')[0];
    check(csvHead === `"time_s","${kase.name}_displacement_cm"`, `CSV header with units: ${csvHead}`);
    // Parametric dialog: a gap sweep of the same scene (10, 15, 20 cm) made into a sweep file and
    // run, then a second parameter (the COR, a list of values) added: the file follows the rows.
    await page.click('header.top nav button[data-tab="parametric"]');
    await page.click('#param-make');
    let sweep = await page.$eval('#sweep-yaml', (t) => t.value);
    check(
      sweep.includes('walls.left.gap, walls.right.gap: {from: "10 cm", to: "20 cm", step: "5 cm"}'),
      'the dialog writes the sweep file',
    );
    await page.click('#param-add');
    await page.evaluate(() => {
      const row = document.querySelectorAll('.param-row')[1];
      const key = row.querySelector('.param-key');
      key.value = 'impact.cor';
      key.dispatchEvent(new Event('change'));
      const mode = row.querySelector('.param-mode');
      mode.value = 'values';
      mode.dispatchEvent(new Event('change'));
      const values = row.querySelector('.param-values');
      values.value = '0.5, 0.9';
      values.dispatchEvent(new Event('input', { bubbles: true }));
    });
    sweep = await page.$eval('#sweep-yaml', (t) => t.value);
    check(sweep.includes('impact.cor: ["0.5", "0.9"]'), 'an added row is in the sweep file without "Make sweep file"');
    await page.click('#param-run');
    await page.waitForFunction(
      () =>
        document.querySelector('#results h1') && document.querySelector('#results h1').textContent.includes('sweep'),
      { timeout: 60000 },
    );
    await page.waitForSelector('#results table.dsrss');
    const rows = await page.$$eval('#results details', (ds) => ds.map((d) => d.querySelector('summary').textContent));
    check(
      rows.some((r) => r === 'sweep.csv'),
      `sweep results shown (${rows.join(', ')})`,
    );
    // The d_SRSS table (companion runs on): its values are dsrss_table.csv's, one row per COR.
    // The Parametric tab shows its own run's progress and state.
    const sweepId = await page.$eval('#param-status', (st) => st.textContent.split(':')[0]);
    const sweepState = await page.$eval('#param-status', (st) => st.dataset.state);
    check(/-sweep$/.test(sweepId) && sweepState === 'done', `the sweep's state on the Parametric tab (${sweepId})`);
    const csv = fs
      .readFileSync(path.join(runsDir, sweepId, 'out', 'dsrss_table.csv'), 'utf8')
      .trim()
      .split('\n');
    const dsrssCol = csv[0].split(',').indexOf('d_srss_m');
    const shown = await page.$$eval('#results table.dsrss .d-srss', (es) => es.map((e) => Number(e.dataset.si)));
    check(
      shown.length === csv.length - 1 && shown.every((v, i) => v === Number(csv[i + 1].split(',')[dsrssCol])),
      `d_SRSS on the page equals dsrss_table.csv (${shown.map((v) => (v * 100).toFixed(2)).join(', ')} cm)`,
    );
    // sweep.csv over the gap: one series per COR, not one zig-zag through both.
    const labels = await page.evaluate(() =>
      window.kimp
        .charts()
        .find((c) => c.title.startsWith('sweep.csv'))
        .plot.series.slice(1)
        .map((x) => x.label),
    );
    check(
      labels.length === 2 && labels[0] === 'impact.cor = 0.5' && labels[1] === 'impact.cor = 0.9',
      `sweep chart grouped by the second parameter (${labels.join(' | ')})`,
    );
    await page.screenshot({ path: path.join(artefacts, 'gui_sweep.png'), fullPage: true });
  });
}

runMain(main);
