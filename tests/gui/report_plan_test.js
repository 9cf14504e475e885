// The report of a run in plan (`kimp lumped` of a scene with `plan:`) draws the plan view: the
// slab at its displaced position and the moat wall, a contact point lit at the frame of the
// largest impact force, sitting on the drawn wall; histories per direction and rotation instead
// of 15 "levels"; the energy balance with friction work. A planar run keeps its old view.
// The GUI's results view (the same page code, served by `kimp gui`) shows a plan run's plan view.
// node report_plan_test.js KIMP PLAN_RESULT_DIR PLANAR_RESULT_DIR ARTEFACT_DIR PLAN_SCENE
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');
const { launch, watchedPage, check, runMain, withGuiPage } = require('./browser.js');

/** Distance of point p from the closed polygon `poly` (its edges). */
function distanceToPolygon(poly, p) {
  let best = Infinity;
  for (let i = 0; i < poly.length; ++i) {
    const [a, b] = [poly[i], poly[(i + 1) % poly.length]];
    const [dx, dy] = [b[0] - a[0], b[1] - a[1]];
    const t = Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)));
    best = Math.min(best, Math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy));
  }
  return best;
}

/** Whether p is inside the closed polygon `poly` (even-odd rule). */
function inside(poly, p) {
  let odd = false;
  for (let i = 0, j = poly.length - 1; i < poly.length; j = i++) {
    const [a, b] = [poly[i], poly[j]];
    if (a[1] > p[1] !== b[1] > p[1] && p[0] < ((b[0] - a[0]) * (p[1] - a[1])) / (b[1] - a[1]) + a[0]) odd = !odd;
  }
  return odd;
}

async function openReport(browser, kimpExe, dir, artefacts, name) {
  const html = path.join(artefacts, name + '_report.html');
  execFileSync(kimpExe, ['-q', 'report', dir, '-o', html]);
  const { page, log } = await watchedPage(browser);
  await page.goto('file://' + html, { waitUntil: 'load' });
  await page.waitForSelector('.chart canvas');
  return { page, log };
}

const titles = (page) => page.evaluate(() => window.kimp.charts().map((c) => c.title));

async function checkPlan(browser, kimpExe, dir, artefacts) {
  const summary = JSON.parse(fs.readFileSync(path.join(dir, 'summary.json'), 'utf8'));
  check(summary.plan === true, 'the run is in plan');
  // The frame of the largest impact force, read from the results file (kimp report --json).
  const data = JSON.parse(execFileSync(kimpExe, ['-q', 'report', dir, '--json'], { maxBuffer: 1 << 28 }));
  const ds = data.h5['lumped.h5'].datasets;
  const force = ds['/lumped/default/history/contact_force/value'].data;
  const time = ds['/lumped/default/history/contact_force/time'].data;
  const names = ds['/lumped/default/contact_names'].data;
  let peak = { f: 0, i: 0, k: 0 };
  force.forEach((row, i) =>
    row.forEach((f, k) => {
      if (f > peak.f) peak = { f: f, i: i, k: k };
    }),
  );
  check(peak.f > 0, `largest sampled impact force ${(peak.f * 1e-6).toFixed(3)} MN of ${names[peak.k]} ` +
    `at t = ${time[peak.i]} s`);

  const { page, log } = await openReport(browser, kimpExe, dir, artefacts, 'plan');
  const shape = () =>
    page.evaluate(() => {
      const pts = (sel) => {
        const p = document.querySelector('svg.plan-view ' + sel);
        return p ? p.getAttribute('points').trim().split(/\s+/).map((s) => s.split(',').map(Number)) : null;
      };
      return {
        slab: pts('polygon.slab'),
        rest: pts('polygon.slab-rest'),
        wall: pts('polygon.wall'),
        contacts: document.querySelectorAll('svg.plan-view circle.contact').length,
        active: Array.from(document.querySelectorAll('svg.plan-view circle.contact.active')).map((c) => ({
          name: c.getAttribute('data-contact'),
          at: [Number(c.getAttribute('cx')), Number(c.getAttribute('cy'))],
        })),
      };
    });
  const s0 = await shape();
  check(s0.slab && s0.slab.length === 4 && s0.wall && s0.wall.length === 4, 'plan view: slab and wall polygons drawn');
  check(s0.contacts === names.length, `every contact point drawn (${s0.contacts} of ${names.length})`);
  check(s0.active.length === 0, 'no contact lit at t = 0');
  const restInside = await page.$$eval('svg.plan-view circle.contact', (cs) =>
    cs.map((c) => [Number(c.getAttribute('cx')), Number(c.getAttribute('cy'))]),
  );
  check(restInside.every((p) => inside(s0.wall, p)), 'at rest every contact point is inside the drawn wall');
  const moved0 = Math.max(...s0.slab.map((p, j) => Math.hypot(p[0] - s0.rest[j][0], p[1] - s0.rest[j][1])));
  check(moved0 < 0.05, `at t = 0 the slab is at rest (${moved0} px)`);
  const wallGap = Math.min(...s0.slab.map((p) => distanceToPolygon(s0.wall, p)));
  check(wallGap > 5, `at rest the slab's corners clear the drawn wall (${wallGap.toFixed(1)} px)`);

  await page.evaluate((t) => window.kimp.animation().seek(t), time[peak.i]);
  const s1 = await shape();
  const lit = s1.active.find((a) => a.name === names[peak.k]);
  check(lit !== undefined, `at the peak frame ${names[peak.k]} is lit (${s1.active.map((a) => a.name).join(', ')})`);
  const onWall = distanceToPolygon(s1.wall, lit.at);
  // In contact the point has crossed the wall face by its indentation (drawn ×exaggeration, as the
  // gap is): on or beyond the drawn wall, while every point at rest is inside it.
  check(
    (!inside(s1.wall, lit.at) || onWall < 0.5) && onWall < wallGap,
    `the lit point is at or past the drawn wall face (${onWall.toFixed(2)} px beyond, gap ${wallGap.toFixed(1)} px)`,
  );
  const moved1 = Math.max(...s1.slab.map((p, j) => Math.hypot(p[0] - s1.rest[j][0], p[1] - s1.rest[j][1])));
  check(moved1 > 0.5 * wallGap, `the slab is drawn displaced at the peak (${moved1.toFixed(1)} px)`);
  await page.$eval('svg.plan-view', (s) => s.scrollIntoView());
  await page.screenshot({ path: path.join(artefacts, 'plan_view.png') });

  const t = await titles(page);
  for (const want of ['displacement along x', 'displacement along y', 'rotation', 'base corner displacements'])
    check(t.includes(want), `chart "${want}"`);
  check(!t.some((x) => /^displacement: /.test(x)), 'no planar per-level displacement chart');
  const dofSeries = await page.evaluate(() =>
    window.kimp.charts().find((c) => c.title === 'rotation').plot.series.slice(1).map((s) => s.label));
  check(dofSeries.length === 5 && dofSeries[0] === 'isolation level', `rotation per level (${dofSeries.join(', ')})`);
  const energy = await page.evaluate(() => {
    const c = window.kimp.charts().find((x) => x.title === 'energy balance');
    return c ? { cats: c.categories, y: Array.from(c.plot.data[1]) } : null;
  });
  const fi = energy ? energy.cats.indexOf('friction work') : -1;
  const friction = summary.cases[0].energy.friction * 1e-6;
  check(fi >= 0 && Math.abs(energy.y[fi] - friction) <= 1e-9 * friction,
    `energy balance shows friction work ${energy && energy.y[fi]} MJ = summary ${friction} MJ`);
  check(log.errors.length === 0, `no console error (${log.errors.join(' | ') || 'none'})`);
}

async function checkPlanar(browser, kimpExe, dir, artefacts) {
  const { page, log } = await openReport(browser, kimpExe, dir, artefacts, 'planar');
  check((await page.$('svg.plan-view')) === null && (await page.$('svg.animation')) !== null,
    'planar run: the elevation animation, no plan view');
  const t = await titles(page);
  check(t.some((x) => /^displacement: /.test(x)) && !t.includes('rotation'),
    `planar run: per-level histories (${t.slice(0, 3).join('; ')})`);
  check(log.errors.length === 0, `no console error (${log.errors.join(' | ') || 'none'})`);
}

/** A plan scene run from the GUI (POST /api/runs) opens in its results view with the plan view. */
async function checkGui(kimpExe, artefacts, sceneFile) {
  await withGuiPage(kimpExe, artefacts, { runs: 'plan_runs' }, async ({ page }) => {
    const scene = fs.readFileSync(sceneFile, 'utf8');
    const id = await page.evaluate(
      async (text) => (await window.kimpGui.postJson('/api/runs', { command: 'lumped', scene: text, name: 'plan' })).id,
      scene,
    );
    await page.waitForFunction(
      async (run) => ['done', 'failed'].includes((await (await fetch(`/api/runs/${run}`)).json()).state),
      { timeout: 30000, polling: 200 },
      id,
    );
    await page.evaluate((run) => window.kimpGui.openResults(run), id);
    await page.waitForSelector('#results svg.plan-view polygon.slab', { timeout: 10000 });
    const drawn = await page.$$eval('#results svg.plan-view polygon.wall, #results svg.plan-view circle.contact', (x) =>
      x.length,
    );
    check(drawn === 9, `GUI results view: the plan view with its wall and 8 contact points (${drawn} shapes)`);
  });
}

async function main() {
  const [kimpExe, planDir, planarDir, artefacts, sceneFile] = process.argv.slice(2);
  fs.mkdirSync(artefacts, { recursive: true });
  const browser = await launch();
  try {
    await checkPlan(browser, kimpExe, planDir, artefacts);
    await checkPlanar(browser, kimpExe, planarDir, artefacts);
  } finally {
    await browser.close();
  }
  await checkGui(kimpExe, artefacts, sceneFile);
}

runMain(main);
