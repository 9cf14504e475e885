// `kimp gui` in headless Chromium opening a large result: a run of tests/gui/big_result_scene.yaml
// (24 storeys, six impact laws, histories every 5 ms), whose results JSON is over 16 MiB as the
// server sends it, opens from the Runs tab with its charts drawn in under 3 s, sent uncompressed
// with its Content-Length, and a progress indicator (spinner, bytes received against the size,
// role status, the results pane aria-busy) is on screen while the JSON downloads and is parsed.
// node gui_big_result_test.js KIMP ARTEFACT_DIR [--opens N]
//   --opens N: open the result N times (the first one checked as above) and print every open's
//   time, for bench/gui_open_result.sh.
'use strict';
const fs = require('fs');
const path = require('path');
const { check, withGuiPage, runMain } = require('./browser.js');

const MIN_BYTES = 16 * 1024 * 1024;
const MAX_OPEN_MS = 3000;

/** Run the scene through the server (POST /api/runs) and wait until it is done; its id. */
async function makeRun(page, scene) {
  const id = await page.evaluate(
    async (text) =>
      (await window.kimpGui.postJson('/api/runs', { command: 'lumped', scene: text, name: '24 storeys, six laws' })).id,
    scene,
  );
  await page.waitForFunction(
    async (run) => ['done', 'failed', 'cancelled'].includes((await (await fetch(`/api/runs/${run}`)).json()).state),
    { timeout: 60000, polling: 200 },
    id,
  );
  const state = await page.evaluate(async (run) => (await (await fetch(`/api/runs/${run}`)).json()).state, id);
  check(state === 'done', `the large run ${id} is done (${state})`);
  return id;
}

/**
 * Click the run's "results" button in the Runs tab and wait until the results pane says its charts
 * are drawn (#results data-loaded = id). What the page showed is sampled at every frame from the
 * click on: {ms (click to drawn), frames: [{t (ms after the click), visible, busy, role, text, value, max, spinning}]}.
 */
async function openFromRunsTab(page, id) {
  await page.click('header.top nav button[data-tab="runs"]');
  const button = `#runs-list tr[data-id="${id}"] button`;
  await page.waitForFunction((b) => document.querySelector(b)?.textContent === 'results', { timeout: 10000 }, button);
  await page.$eval(
    button,
    (b, run) => {
      const pane = document.getElementById('results');
      const open = { t0: performance.now(), loadedAt: null, frames: [] };
      window.kimpOpen = open;
      new MutationObserver(() => {
        if (pane.dataset.loaded === run && open.loadedAt === null) open.loadedAt = performance.now();
      }).observe(pane, { attributes: true });
      const sample = () => {
        const box = pane.querySelector('.results-loading');
        if (box) {
          const r = box.getBoundingClientRect();
          const bar = box.querySelector('progress');
          const spinner = box.querySelector('.spinner');
          open.frames.push({
            t: performance.now() - open.t0,
            visible: r.width > 0 && r.height > 0 && getComputedStyle(box).visibility === 'visible',
            busy: pane.getAttribute('aria-busy'),
            role: box.getAttribute('role'),
            text: box.textContent,
            value: bar ? bar.value : null,
            max: bar ? bar.max : null,
            spinning: spinner ? getComputedStyle(spinner).animationName : 'none',
          });
        }
        if (open.loadedAt === null) requestAnimationFrame(sample);
      };
      requestAnimationFrame(sample);
      b.click();
    },
    id,
  );
  const patience = 10 * MAX_OPEN_MS;
  await page
    .waitForFunction(() => window.kimpOpen.loadedAt !== null, { timeout: patience, polling: 50 })
    .catch(() => check(false, `the result opened within ${patience} ms of the click`));
  return page.evaluate(() => ({ ms: window.kimpOpen.loadedAt - window.kimpOpen.t0, frames: window.kimpOpen.frames }));
}

async function main() {
  const args = process.argv.slice(2);
  const [kimpExe, artefacts] = args;
  const opensAt = args.indexOf('--opens');
  const opens = opensAt >= 0 ? Number(args[opensAt + 1]) : 1;
  const scene = fs.readFileSync(path.join(__dirname, 'big_result_scene.yaml'), 'utf8');
  await withGuiPage(kimpExe, artefacts, { runs: 'gui_big_result_runs' }, async ({ page }) => {
    const id = await makeRun(page, scene);
    // The response as the browser received it (it offers gzip, deflate and br).
    const responses = [];
    page.on('response', (r) => {
      if (r.url().endsWith(`/api/runs/${id}/data`)) responses.push(r.headers());
    });

    const first = await openFromRunsTab(page, id);
    const headers = responses[0] || {};
    const bytes = Number(headers['content-length']);
    const encoding = headers['content-encoding'] || 'none';
    console.log(`open of the ${(bytes / 1e6).toFixed(1)} MB result, click to charts drawn: ${first.ms.toFixed(0)} ms`);
    check(bytes >= MIN_BYTES, `the results JSON is ${(bytes / 1e6).toFixed(2)} MB (>= 16 MiB) as the server sends it`);
    check(encoding === 'none', `sent uncompressed (Content-Encoding: ${encoding})`);
    check(first.ms < MAX_OPEN_MS, `the result opens in ${first.ms.toFixed(0)} ms (< ${MAX_OPEN_MS} ms)`);

    // The progress indicator, on screen in the frames painted while the JSON came and was parsed.
    const shown = first.frames.filter((f) => f.visible && f.busy === 'true' && f.role === 'status');
    check(
      shown.length > 0,
      `a progress indicator (role status, #results aria-busy) was visible in ${shown.length} of ` +
        `${first.frames.length} frames before the charts were drawn`,
    );
    check(
      shown.every((f) => f.spinning === 'kimp-spin'),
      'its spinner turns in every frame it is shown (CSS animation)',
    );
    const megabytes = (bytes / 1e6).toFixed(1);
    const read = shown.find((f) => f.max === bytes && f.value === bytes && f.text.includes(`${megabytes} MB`));
    check(
      read !== undefined,
      `it counted the bytes against the Content-Length (bar ${bytes} of ${bytes}) and said "${read && read.text}"`,
    );
    // When each of its lines was first painted (ms after the click), where the time goes.
    const phases = new Map();
    for (const f of shown) {
      const line = f.text.replace(/[\d.]+ of/, 'N of');
      if (!phases.has(line)) phases.set(line, f.t);
    }
    for (const [line, t] of phases) console.log(`  ${t.toFixed(0).padStart(5)} ms: ${line}`);

    // Then the charts, and no indicator left.
    const after = await page.evaluate(() => ({
      busy: document.getElementById('results').getAttribute('aria-busy'),
      indicator: document.querySelectorAll('#results .results-loading').length,
      charts: document.querySelectorAll('#results .chart canvas').length,
      text: document.getElementById('results').textContent,
    }));
    const laws = ['linear', 'kelvin_voigt', 'modified_kelvin_voigt', 'jankowski', 'hertzdamp', 'hysteretic'];
    check(
      after.busy === 'false' && after.indicator === 0 && after.charts >= 5 && laws.every((l) => after.text.includes(l)),
      `then ${after.charts} charts drawn with the six cases, the indicator gone, aria-busy false`,
    );
    await page.screenshot({ path: path.join(artefacts, 'gui_big_result.png') });

    for (let i = 1; i < opens; ++i) {
      const again = await openFromRunsTab(page, id);
      console.log(`open ${i + 1}: ${again.ms.toFixed(0)} ms`);
    }
  });
}

runMain(main);
