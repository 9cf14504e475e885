// `kimp gui` in headless Chromium, the Parametric tab: a gap sweep over two impact laws, each law
// paired with its own k (a list of maps in the sweep file); a law given the wrong k fails with the
// sweep's own message on the Parametric tab; the right pairs run, with their progress and state on
// that tab, and the charts plot against the swept parameters (the gap in cm, the laws by name).
// node gui_sweep_test.js KIMP ARTEFACT_DIR
'use strict';
const fs = require('fs');
const path = require('path');
const { check, setField, runAndWait, withGuiPage, runMain } = require('./browser.js');

/** Tick the laws of the impact.law row and type a k for `typed` (law -> k). */
async function chooseLaws(page, laws, typed) {
  await page.evaluate(
    (ls, ks) => {
      const row = document.querySelectorAll('.param-row')[1];
      for (const b of row.querySelectorAll('.param-option')) b.checked = ls.includes(b.value);
      for (const k of row.querySelectorAll('.param-k')) k.value = ks[k.dataset.law] || '';
      row.dispatchEvent(new Event('change'));
    },
    laws,
    typed,
  );
}

async function main() {
  const [kimpExe, artefacts] = process.argv.slice(2);
  await withGuiPage(kimpExe, artefacts, { runs: 'gui_sweep_runs' }, async ({ page, log, runsDir }) => {
    await setField(page, 'building.n_storeys', '3');
    await setField(page, 'ground_motion.duration', '6 s');
    await page.click('header.top nav button[data-tab="parametric"]');
    await page.click('#param-add');
    await page.evaluate(() => {
      const key = document.querySelectorAll('.param-row')[1].querySelector('.param-key');
      key.value = 'impact.law';
      key.dispatchEvent(new Event('change'));
    });

    // hertzdamp given a k in kN/mm (n = 1) instead of kN/mm^1.5: the sweep's message, on this tab.
    await chooseLaws(page, ['kelvin_voigt', 'hertzdamp'], { hertzdamp: '2500 kN/mm' });
    await page.click('#param-run');
    await page.waitForFunction(() => document.querySelector('#param-error').textContent.length > 0, {
      timeout: 60000,
    });
    const error = await page.$eval('#param-error', (e) => e.textContent);
    const failed = await page.$eval('#param-status', (e) => e.dataset.state || '');
    check(/impact\.k|kN\/mm/.test(error), `a wrong k refused on the Parametric tab (${failed}): ${error.split('\n')[0]}`);

    // Each law with its own k: the sweep file pairs them.
    await chooseLaws(page, ['kelvin_voigt', 'hertzdamp'], {});
    const sweep = await page.$eval('#sweep-yaml', (t) => t.value);
    check(
      sweep.includes(
        'impact.law: [{impact.law: kelvin_voigt, impact.k: "2500 kN/mm", label: kelvin_voigt}, ' +
          '{impact.law: hertzdamp, impact.k: "750 kN/mm^1.5", label: hertzdamp}]',
      ),
      'each law paired with its k in the sweep file',
    );
    const id = await runAndWait(page, {
      button: '#param-run',
      status: '#param-status',
      result: '#results table.dsrss',
      timeout: 90000,
    });
    const progress = await page.$eval('#param-progress', (e) => e.value);
    check(progress === 1, `the sweep's progress on the Parametric tab (${id}: ${progress})`);
    const errorAfter = await page.$eval('#param-error', (e) => e.textContent);
    check(errorAfter === '', 'no error left on the Parametric tab');
    const csv = fs.readFileSync(path.join(runsDir, id, 'out', 'sweep.csv'), 'utf8').trim().split('\n');
    const head = csv[0].split(',');
    const ok = csv.slice(1).filter((r) => r.includes(',ok'));
    check(head.includes('impact.law') && ok.length === csv.length - 1, `${csv.length - 1} cases ran ok, by law`);

    // Charts against the swept parameters: the gap with its unit, the laws by name.
    const axes = await page.evaluate(() =>
      window.kimp.charts().map((c) => ({ title: c.title, x: c.xlabel, categories: c.categories })),
    );
    const dsrss = axes.find((a) => a.title.startsWith('required gap'));
    const sweepChart = axes.find((a) => a.title.startsWith('sweep.csv'));
    check(
      dsrss && dsrss.x === 'impact.law' && JSON.stringify(dsrss.categories) === '["kelvin_voigt","hertzdamp"]',
      `d_req / d_SRSS over the laws (x: ${dsrss && dsrss.x}, ${dsrss && dsrss.categories})`,
    );
    check(
      sweepChart && /gap.*(\(cm\)|_cm)$/.test(sweepChart.x),
      `sweep.csv over the gap in cm (x: ${sweepChart && sweepChart.x})`,
    );
    await page.screenshot({ path: path.join(artefacts, 'gui_sweep_laws.png'), fullPage: true });
    // The refused sweep's 400 is the only console error the browser may log.
    log.errors = log.errors.filter((e) => !/status of 400/.test(e));
  });
}

runMain(main);
