// `kimp gui` in headless Chromium, the runs as a user keeps and compares them: a run with a name
// and notes, its complete saved scene (every default written out), the scene as run echoed in the
// results, the Runs tab that follows new runs by itself and lists no hidden file, a rename, the
// overlay legend by name, a run reopened in the editor, a delete, and the form kept across a
// reload of the page. Screenshots go to ARTEFACT_DIR.
// node gui_runs_test.js KIMP ARTEFACT_DIR
'use strict';
const fs = require('fs');
const path = require('path');
const { check, setField, setInput, runAndWait, withGuiPage, runMain } = require('./browser.js');
const jsyaml = require(path.join(__dirname, '..', '..', 'gui', 'node_modules', 'js-yaml'));

const SMALL =
  'building:\n  n_storeys: 3\nwalls:\n  left:\n    gap: "8 cm"\n  right:\n    gap: "8 cm"\n' +
  'ground_motion:\n  duration: "6 s"\n';

/** Every key path of the leaves of `obj` (maps only; a list is a leaf). */
function leafPaths(obj, prefix, out) {
  for (const [k, v] of Object.entries(obj)) {
    const p = prefix ? `${prefix}.${k}` : k;
    if (v && typeof v === 'object' && !Array.isArray(v)) leafPaths(v, p, out);
    else out.push(p);
  }
  return out;
}

const at = (obj, p) => p.split('.').reduce((o, k) => (o && typeof o === 'object' ? o[k] : undefined), obj);

async function runScene(page, yaml, name, notes) {
  await page.$eval('#scene-yaml', (t, y) => {
    t.value = y;
  }, yaml);
  await page.$eval('#scene-apply', (b) => b.click());
  await setInput(page, '#run-name', name);
  await setInput(page, '#run-notes', notes);
  return runAndWait(page, { button: '#scene-run', status: '#run-status', result: '#results .peaks', timeout: 60000 });
}

/** What the editor shows of the small scene: its storeys, left gap and run name. */
function editorState(page) {
  return page.evaluate(() => ({
    storeys: document.querySelector('#scene-form input[data-path="building.n_storeys"]').value,
    gap: document.querySelector('#scene-form input[data-path="walls.left.gap"]').value,
    name: document.querySelector('#run-name').value,
  }));
}

async function main() {
  const [kimpExe, artefacts] = process.argv.slice(2);
  await withGuiPage(kimpExe, artefacts, { runs: 'gui_runs_runs' }, async ({ page, url, runsDir }) => {
    // A named run with notes.
    const first = await runScene(page, SMALL, 'gap 8 cm', 'the small scene, synthetic motion');
    const meta = JSON.parse(fs.readFileSync(path.join(runsDir, first, 'meta.json'), 'utf8'));
    check(meta.name === 'gap 8 cm' && meta.notes === 'the small scene, synthetic motion', 'name and notes kept');
    const h1 = await page.$eval('#results h1', (e) => e.textContent);
    check(h1.includes('gap 8 cm'), `the results are titled by the run's name: ${h1}`);
    const notesShown = await page.$eval('#results .run-notes-shown', (e) => e.textContent);
    check(notesShown === 'the small scene, synthetic motion', 'the notes are shown with the results');

    // The saved scene is complete: every key of --print-defaults, with the run's own values.
    const saved = jsyaml.load(fs.readFileSync(path.join(runsDir, first, 'scene.yaml'), 'utf8'));
    const defaults = jsyaml.load(await (await fetch(url + 'api/defaults/lumped')).text());
    const missing = leafPaths(defaults, '', []).filter((p) => at(saved, p) === undefined);
    check(missing.length === 0, `saved scene.yaml has every default key (${missing.join(', ') || 'none missing'})`);
    check(
      saved.building.n_storeys === 3 && saved.walls.left.gap === '8 cm' && saved.impact.law === defaults.impact.law,
      `saved scene: the run's values (n_storeys ${saved.building.n_storeys}, gap ${saved.walls.left.gap}) and the ` +
        `defaults written out (impact.law ${saved.impact.law})`,
    );
    // The inputs echoed in the results: the scene as run (lumped.h5 /input/scene).
    const inputs = await page.$eval('#results .inputs-scene', (e) => e.textContent);
    check(/n_storeys: 3\b/.test(inputs) && /output_interval/.test(inputs), 'the scene as run is in the results');

    // The Runs tab follows a run started elsewhere without a click, and lists no hidden file.
    await page.click('header.top nav button[data-tab="runs"]');
    // Long enough to be cancelled (about 10 s): 3e7 steps of 5e-7 s, 30 storeys.
    const long =
      SMALL.replace('duration: "6 s"', 'duration: "15 s"').replace('n_storeys: 3', 'n_storeys: 30') +
      'integration:\n  dt: "5e-7 s"\n';
    const second = await page.evaluate(
      async (scene) =>
        (
          await window.kimpGui.postJson('/api/runs', { command: 'lumped', scene: scene, name: 'to cancel' })
        ).id,
      long,
    );
    await page.waitForSelector(`#runs-list tr[data-id="${second}"]`, { timeout: 10000 });
    check(true, 'the Runs tab shows a new run by itself');
    await page.evaluate((id) => window.kimpGui.postJson(`/api/runs/${id}/cancel`, {}), second);
    await page.waitForFunction(
      (id) => /cancelled/.test(document.querySelector(`#runs-list tr[data-id="${id}"] .run-state`).textContent),
      { timeout: 10000 },
      second,
    );
    fs.mkdirSync(path.join(runsDir, second, 'out'), { recursive: true });
    fs.writeFileSync(path.join(runsDir, second, 'out', '.kimp.lock'), '1\n');
    fs.writeFileSync(path.join(runsDir, second, 'out', 'partial.csv'), 'a\n1\n');
    await page.waitForFunction(
      (id) => /partial\.csv/.test(document.querySelector(`#runs-list tr[data-id="${id}"]`).textContent),
      { timeout: 10000 },
      second,
    );
    const links = await page.$$eval(`#runs-list tr[data-id="${second}"] a`, (as) => as.map((a) => a.textContent));
    check(!links.some((l) => l.includes('.kimp.lock')), `no .kimp.lock among the files (${links.join(', ')})`);

    // A second run, then the first renamed: the overlay legend reads the names.
    await page.click('header.top nav button[data-tab="scene"]');
    const third = await runScene(page, SMALL.replace('"8 cm"', '"9 cm"').replace('"8 cm"', '"9 cm"'), 'gap 9 cm', '');
    await page.click('header.top nav button[data-tab="runs"]');
    await page.waitForSelector(`#runs-list tr[data-id="${first}"] .run-name`);
    await page.$eval(`#runs-list tr[data-id="${first}"] .run-name`, (i) => {
      i.value = 'gap 8 cm (renamed)';
      i.dispatchEvent(new Event('change'));
    });
    await page.waitForFunction(
      async (id) => (await (await fetch(`/api/runs/${id}`)).json()).name === 'gap 8 cm (renamed)',
      { timeout: 5000 },
      first,
    );
    check(true, 'a run renamed in the Runs tab');
    await page.evaluate((id, other) => window.kimpGui.openResults(id, [other]), third, first);
    await page.waitForFunction(() => document.querySelectorAll('#results .case-box').length === 2);
    const labels = await page.evaluate(() =>
      window.kimp
        .charts()[0]
        .plot.series.slice(1)
        .map((s) => s.label),
    );
    check(
      labels.length === 2 && labels[0] === 'gap 9 cm: default' && labels[1] === 'gap 8 cm (renamed): default',
      `overlay legend by run name: ${labels.join(' | ')}`,
    );
    await page.screenshot({ path: path.join(artefacts, 'gui_overlay_named.png') });

    // Reopen the first run in the editor: its scene and name in the form.
    await page.click('header.top nav button[data-tab="runs"]');
    await page.waitForSelector(`#runs-list tr[data-id="${first}"] .run-edit`);
    // Clicked in the page at once: the tab redraws its table every 2 s.
    await page.$eval(`#runs-list tr[data-id="${first}"] .run-edit`, (b) => b.click());
    await page.waitForFunction(() => document.querySelector('#pane-scene').classList.contains('active'));
    const reopened = await editorState(page);
    check(
      reopened.storeys === '3' && reopened.gap === '8 cm' && reopened.name === 'gap 8 cm (renamed)',
      `run reopened in the editor (n_storeys ${reopened.storeys}, gap ${reopened.gap}, name "${reopened.name}")`,
    );

    // Delete the cancelled run: its row and its directory go.
    await page.click('header.top nav button[data-tab="runs"]');
    await page.waitForSelector(`#runs-list tr[data-id="${second}"] .run-delete`);
    await page.$eval(`#runs-list tr[data-id="${second}"] .run-delete`, (b) => b.click());
    await page.waitForFunction((id) => !document.querySelector(`#runs-list tr[data-id="${id}"]`), {}, second);
    check(!fs.existsSync(path.join(runsDir, second)), 'a deleted run leaves no directory');
    const refused = (
      await fetch(`${url}api/runs/${second}/delete`, { method: 'POST', headers: { 'X-Kimp-Request': '1' }, body: '{}' })
    ).status;
    check(refused === 404, `deleting it again: HTTP ${refused}`);

    // The session survives a reload: the form, the run name and the tab.
    await page.click('header.top nav button[data-tab="scene"]');
    await setField(page, 'building.n_storeys', '5');
    await setInput(page, '#run-name', 'after reload');
    await page.reload({ waitUntil: 'load' });
    await page.waitForSelector('body[data-ready="1"]', { timeout: 15000 });
    const kept = await editorState(page);
    check(
      kept.storeys === '5' && kept.gap === '8 cm' && kept.name === 'after reload',
      `the form kept across a reload (n_storeys ${kept.storeys}, gap ${kept.gap}, name "${kept.name}")`,
    );
    await page.screenshot({ path: path.join(artefacts, 'gui_runs.png') });
  });
}

runMain(main);
