// `kimp gui` in headless Chromium, the yielding moat wall's inputs: the lumped `yielding` wall
// law's parameters set through the scene form reach the run (summary.json's walls carry the
// capacity and failure limit set on the page), and the keys an inelastic study's yielding wall
// element reads (materials, interface, the pushover's path) are form fields that write the YAML
// scene the server validates.
// node gui_yielding_wall_test.js KIMP ARTEFACT_DIR
'use strict';
const fs = require('fs');
const path = require('path');
const { check, setField, setInput, withGuiPage, runMain } = require('./browser.js');

/** Set the select of the scene form at `fieldPath` to `value` and fire its change event. */
async function setChoice(page, fieldPath, value) {
  await page.$eval(
    `#scene-form select[data-path="${fieldPath}"]`,
    (s, v) => {
      s.value = v;
      s.dispatchEvent(new Event('change', { bubbles: true }));
    },
    value,
  );
}

async function main() {
  const [kimpExe, artefacts] = process.argv.slice(2);
  await withGuiPage(kimpExe, artefacts, { runs: 'gui_yielding_runs' }, async ({ page, runsDir }) => {
    // The lumped yielding wall law: 20 m of wall, 50 kN/m capacity (1 MN), 1 cm failure limit.
    await setField(page, 'building.n_storeys', '3');
    await setField(page, 'ground_motion.duration', '6 s');
    for (const side of ['left', 'right']) {
      await setField(page, `walls.${side}.gap`, '4 cm');
      await setField(page, `walls.${side}.sdof_mass`, '50 t');
      await setChoice(page, `walls.${side}.yielding.envelope`, 'bilinear');
      await setField(page, `walls.${side}.yielding.width`, '20 m');
      await setField(page, `walls.${side}.yielding.capacity`, '50 kN/m');
      await setField(page, `walls.${side}.yielding.stiffness`, '10 kN/mm/m');
      await setField(page, `walls.${side}.yielding.hardening_ratio`, '2 %');
      await setField(page, `walls.${side}.yielding.failure_displacement`, '1 cm');
    }
    const yaml = await page.$eval('#scene-yaml', (t) => t.value);
    check(/yielding:/.test(yaml) && /capacity: "50 kN\/m"/.test(yaml), 'the form writes the yielding section');
    await page.click('#scene-run');
    await page.waitForFunction(
      () => document.querySelector('#results .peaks') || document.querySelector('#scene-error').textContent !== '',
      { timeout: 60000 },
    );
    const refused = await page.$eval('#scene-error', (e) => e.textContent.trim());
    check(refused === '', `the scene runs (${refused || 'no error'})`);
    await page.waitForSelector('#results .peaks', { timeout: 60000 });
    const runId = await page.$eval('#run-status', (s) => s.textContent.split(':')[0]);
    const summary = JSON.parse(fs.readFileSync(path.join(runsDir, runId, 'out', 'summary.json'), 'utf8'));
    const walls = summary.cases[0].walls || [];
    check(walls.length === 2, `the run has two yielding walls (${walls.length})`);
    for (const w of walls) {
      check(Math.abs(w.capacity - 1e6) < 1e-3, `${w.name}: capacity 50 kN/m x 20 m = 1 MN (${w.capacity} N)`);
      const limit = w.failure_displacement;
      check(Math.abs(limit - 0.01) < 1e-12, `${w.name}: failure limit 1 cm (${limit} m)`);
    }
    await page.screenshot({ path: path.join(artefacts, 'gui_yielding_wall.png') });

    // The curve envelope: its points typed as YAML into the form's list box (60 kN/m x 20 m =
    // 1.2 MN capacity); the keys the curve sets itself left empty.
    const curve = '- {displacement: 0 mm, force: 0 kN/m}\n- {displacement: 4 mm, force: 40 kN/m}\n';
    for (const side of ['left', 'right']) {
      await setChoice(page, `walls.${side}.yielding.envelope`, 'curve');
      for (const key of ['capacity', 'stiffness', 'hardening_ratio'])
        await setField(page, `walls.${side}.yielding.${key}`, '');
      await setInput(
        page,
        `#scene-form textarea[data-path="walls.${side}.yielding.curve"]`,
        curve + '- {displacement: 2 cm, force: 60 kN/m}\n',
        true,
      );
    }
    const curveYaml = await page.$eval('#scene-yaml', (t) => t.value);
    check(/envelope: "?curve"?/.test(curveYaml) && /force: "?60 kN\/m"?/.test(curveYaml), `the form writes the curve:\n${curveYaml}`);
    const before = await page.$eval('#run-status', (s) => s.textContent);
    await page.$eval('#scene-run', (b) => b.click());
    await page.waitForFunction(
      (prev) => {
        const s = document.querySelector('#run-status');
        return s.textContent !== prev && s.dataset.state === 'done' && document.querySelector('#results .peaks');
      },
      { timeout: 60000 },
      before,
    );
    const curveRun = await page.$eval('#run-status', (s) => s.textContent.split(':')[0]);
    const curveSummary = JSON.parse(fs.readFileSync(path.join(runsDir, curveRun, 'out', 'summary.json'), 'utf8'));
    for (const w of curveSummary.cases[0].walls || [])
      check(Math.abs(w.capacity - 1.2e6) < 1e-3, `${w.name}: the curve's capacity 60 kN/m x 20 m (${w.capacity} N)`);
    // A convex point is refused naming the item.
    await setInput(
      page,
      '#scene-form textarea[data-path="walls.left.yielding.curve"]',
      curve + '- {displacement: 5 mm, force: 60 kN/m}\n',
      true,
    );
    await page.$eval('#scene-validate', (b) => b.click());
    await page.waitForFunction(() => /curve\[2\]/.test(document.querySelector('#scene-error').textContent), {
      timeout: 15000,
    });

    // The study: its yielding wall element's inputs are form fields.
    await page.select('#scene-command', 'study');
    await page.waitForSelector('#scene-form input[data-path="fem.pushover.displacement"]');
    // The elastic wall is the default; Mohr-Coulomb sand makes the study inelastic.
    await setChoice(page, 'fem.materials.soil.model', 'mohr_coulomb');
    await setChoice(page, 'fem.interface.model', 'contact');
    await setField(page, 'fem.pushover.displacement', '40 mm');
    await setField(page, 'fem.pushover.unload_at', '20 mm');
    await setField(page, 'fem.pushover.increment', '2 mm');
    const study = await page.$eval('#scene-yaml', (t) => t.value);
    check(
      /model: "?mohr_coulomb"?/.test(study) && /model: "?contact"?/.test(study) && /displacement: "40 mm"/.test(study) && /unload_at:/.test(study),
      `the study form writes the materials and the pushover path:\n${study}`,
    );
    await page.$eval('#scene-validate', (b) => b.click());
    await page.waitForFunction(() => document.querySelector('#scene-error').textContent !== '', {
      timeout: 15000,
    });
    const verdict = await page.$eval('#scene-error', (e) => e.textContent.trim());
    check(verdict === 'scene is valid', `the server validates the study scene (${verdict})`);
  });
}

runMain(main);
