// `kimp gui` in headless Chromium, a scene in plan with yielding wall faces and modal damping: the
// scene form's plan keys (`plan.damping`, the `plan.moat.yielding` list) write the YAML scene the
// run gets; the run's results view and its `kimp report` state the damping model and list each
// yielding face's peak force against its capacity (per metre × the face's length), residual
// displacement and failure time, as summary.json and lumped.h5 (`walls/face_<k>`, with units) hold.
// node gui_plan_yielding_test.js KIMP ARTEFACT_DIR
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');
const { check, setField, setInput, withGuiPage, launch, watchedPage, runMain } = require('./browser.js');

// Faces 1 and 3 (the struck ones, at +x and −x) of the 20.08 m square moat (20 m slab at 4 cm)
// carry a weak wall-and-backfill part: 5 kN/mm and 20 kN per metre, face 1 failing at 2 mm.
const YIELDING = [
  '- {face: 1, stiffness: "5 kN/mm/m", capacity: "20 kN/m", failure_displacement: "0.2 cm"}',
  '- {face: 3, stiffness: "5 kN/mm/m", capacity: "20 kN/m"}',
].join('\n');
const FACE_LENGTH = 20.08;

/** The rows of the yielding-faces table of the results in `root` (the GUI's #results or the report). */
function facesTable(page, root) {
  return page.evaluate((r) => {
    const t = document.querySelector(`${r} table.yielding-faces`);
    if (!t) return null;
    return Array.from(t.querySelectorAll('tbody tr')).map((tr) =>
      Array.from(tr.querySelectorAll('td')).map((td) => {
        const peak = td.querySelector('span.peak');
        return peak ? { si: Number(peak.dataset.si), text: td.textContent.trim() } : td.textContent.trim();
      }),
    );
  }, root);
}

/** The table's rows against summary.json's yielding_walls (order, values, failure). */
function checkFaces(rows, walls, where) {
  check(rows && rows.length === walls.length, `${where}: one row per yielding face (${rows && rows.length})`);
  walls.forEach((w, i) => {
    const r = rows[i];
    check(r[0] === String(w.face), `${where}: row ${i} is face ${w.face} (${r[0]})`);
    check(r[1].si === w.peak_force && w.peak_force > 0, `${where}: face ${w.face} peak force ${r[1].text}`);
    check(r[2].si === w.capacity, `${where}: face ${w.face} capacity ${r[2].text}`);
    check(r[3].si === w.peak_resistance, `${where}: face ${w.face} peak resistance ${r[3].text}`);
    check(r[6].si === w.residual_displacement, `${where}: face ${w.face} residual ${r[6].text}`);
    const failed = w.failed ? /^yes, at [0-9.]+ s$/.test(r[7]) : r[7] === 'no';
    check(failed, `${where}: face ${w.face} failed column "${r[7]}" (summary failed ${w.failed})`);
  });
}

async function dampingText(page, root) {
  return page.evaluate((r) => {
    const p = document.querySelector(`${r} p.damping`);
    return p ? { model: p.dataset.model, text: p.textContent } : null;
  }, root);
}

async function main() {
  const [kimpExe, artefacts] = process.argv.slice(2);
  let outDir;
  await withGuiPage(kimpExe, artefacts, { runs: 'gui_plan_yielding_runs' }, async ({ page, runsDir }) => {
    // The plan section through the form: the default building on a 20 m slab, 1 m eccentric, at 4 cm.
    await setField(page, 'ground_motion.duration', '6 s');
    await setField(page, 'integration.output_interval', '0.01 s');
    await setField(page, 'plan.eccentricity_x', '1 m');
    await setField(page, 'plan.angle', '30');
    await setField(page, 'plan.moat.gap', '4 cm');
    await setField(page, 'plan.moat.friction', '0.3');
    await page.$eval('#scene-form select[data-path="plan.damping"]', (s) => {
      s.value = 'modal';
      s.dispatchEvent(new Event('change', { bubbles: true }));
    });
    await setInput(page, '#scene-form textarea[data-path="plan.moat.yielding"]', YIELDING, true);
    const yaml = await page.$eval('#scene-yaml', (t) => t.value);
    check(/damping: "?modal"?/.test(yaml), 'the form writes plan.damping: modal');
    check(/yielding:/.test(yaml) && /capacity: "20 kN\/m"/.test(yaml) && /face: 3/.test(yaml),
      `the form writes the yielding faces:\n${yaml}`);

    // Run: the page shows either the error the run was refused with or the plan view.
    await page.click('#scene-run');
    const outcome = await page.waitForFunction(
      () =>
        document.querySelector('#scene-error').textContent.trim() ||
        (document.querySelector('#results svg.plan-view') ? 'plan view' : ''),
      { timeout: 90000 },
    );
    const shown = await outcome.jsonValue();
    check(shown === 'plan view', `the scene runs and its results show the plan view (${shown})`);
    const runId = await page.$eval('#run-status', (s) => s.textContent.split(':')[0]);
    outDir = path.join(runsDir, runId, 'out');
    const summary = JSON.parse(fs.readFileSync(path.join(outDir, 'summary.json'), 'utf8'));
    const c = summary.cases[0];
    check(c.damping && c.damping.model === 'modal', `summary.json: damping model modal (${JSON.stringify(c.damping)})`);
    const walls = c.yielding_walls || [];
    check(walls.length === 2 && walls[0].face === 1 && walls[1].face === 3, 'summary.json: faces 1 and 3 yield');
    for (const w of walls) {
      const capacity = 20e3 * FACE_LENGTH;
      check(Math.abs(w.capacity - capacity) <= 1e-9 * capacity,
        `face ${w.face}: capacity 20 kN/m × ${FACE_LENGTH} m = ${capacity} N (${w.capacity} N)`);
    }
    check(walls.every((w) => w.peak_force > 0 && w.peak_resistance > 0), 'both yielding faces are struck');
    check(walls.some((w) => w.failed && w.failure_time > 0), 'a yielding face fails, with its time');
    check(summary.units.yielding_walls && summary.units.yielding_walls.capacity === 'N' &&
      summary.units.yielding_walls.residual_displacement === 'm', 'summary.json: the yielding faces\' units');

    const gui = await dampingText(page, '#results');
    check(gui && gui.model === 'modal' && /modal/.test(gui.text), `GUI results: damping stated (${gui && gui.text})`);
    checkFaces(await facesTable(page, '#results'), walls, 'GUI results');
    await page.screenshot({ path: path.join(artefacts, 'gui_plan_yielding.png'), fullPage: true });
  });

  // lumped.h5 (read as `kimp report --json` prints it, to 7 digits): the faces with units, the
  // damping model as an attribute.
  const near = (a, b) => Math.abs(a - b) <= 1e-6 * Math.abs(b);
  const data = JSON.parse(execFileSync(kimpExe, ['-q', 'report', outDir, '--json'], { maxBuffer: 1 << 28 }));
  const h5 = data.h5['lumped.h5'];
  const summary = JSON.parse(fs.readFileSync(path.join(outDir, 'summary.json'), 'utf8'));
  for (const w of summary.cases[0].yielding_walls) {
    const g = `/lumped/default/walls/face_${w.face}/`;
    const cap = h5.datasets[g + 'capacity'];
    const residual = h5.datasets[g + 'residual_displacement'];
    check(cap && near(cap.data, w.capacity) && cap.units === 'N', `lumped.h5 ${g}capacity in N`);
    check(residual && near(residual.data, w.residual_displacement) && residual.units === 'm',
      `lumped.h5 ${g}residual_displacement in m`);
    check(!w.failed || near(h5.datasets[g + 'failure_time'].data, w.failure_time), `lumped.h5 ${g}failure_time`);
  }
  const attrs = h5.groups['/lumped/default'];
  check(attrs.damping === 'modal', `lumped.h5 /lumped/default damping = ${attrs.damping}`);

  // `kimp report` of the run: the same statements.
  const html = path.join(artefacts, 'plan_yielding_report.html');
  execFileSync(kimpExe, ['-q', 'report', outDir, '-o', html]);
  const browser = await launch();
  try {
    const { page, log } = await watchedPage(browser);
    await page.goto('file://' + html, { waitUntil: 'load' });
    await page.waitForSelector('svg.plan-view');
    const report = await dampingText(page, 'body');
    check(report && report.model === 'modal', `report: damping stated (${report && report.text})`);
    checkFaces(await facesTable(page, 'body'), summary.cases[0].yielding_walls, 'report');
    check(log.errors.length === 0, `no console error (${log.errors.join(' | ') || 'none'})`);
  } finally {
    await browser.close();
  }
}

runMain(main);
