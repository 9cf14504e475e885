// Shared helpers of the browser tests: the system Chromium driven by puppeteer-core (from
// gui/node_modules; no browser is ever downloaded), console-error and network-request capture.
'use strict';
const path = require('path');
const fs = require('fs');
const { spawn } = require('child_process');
const puppeteer = require(path.join(__dirname, '..', '..', 'gui', 'node_modules', 'puppeteer-core'));

const CHROMIUM = process.env.KIMP_CHROMIUM || '/usr/bin/chromium';

async function launch() {
  const args = [
    '--headless=new',
    '--disable-gpu',
    '--no-first-run',
    '--disable-extensions',
    '--disable-background-networking',
    '--disable-component-update',
    '--disable-sync',
    '--disable-default-apps',
    '--disable-dev-shm-usage',
  ];
  if (process.getuid && process.getuid() === 0) args.push('--no-sandbox');
  return puppeteer.launch({ executablePath: CHROMIUM, headless: true, args: args });
}

/** A page that records console errors, page errors and every request's URL. */
async function watchedPage(browser, downloadDir) {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 900 });
  const log = { errors: [], requests: [] };
  page.on('console', (m) => {
    if (m.type() === 'error') log.errors.push(m.text());
  });
  page.on('pageerror', (e) => log.errors.push(String(e)));
  page.on('request', (r) => log.requests.push(r.url()));
  if (downloadDir) {
    fs.mkdirSync(downloadDir, { recursive: true });
    const cdp = await page.createCDPSession();
    await cdp.send('Browser.setDownloadBehavior', { behavior: 'allow', downloadPath: downloadDir });
  }
  return { page: page, log: log };
}

async function waitForFile(file, ms) {
  const end = Date.now() + ms;
  while (Date.now() < end) {
    if (fs.existsSync(file) && fs.statSync(file).size > 0) return fs.readFileSync(file, 'utf8');
    await new Promise((r) => setTimeout(r, 100));
  }
  throw new Error(`no file ${file} after ${ms} ms`);
}

function check(condition, message) {
  if (!condition) throw new Error('check failed: ' + message);
  console.log('ok: ' + message);
}

/** `kimp gui` on a free port with its runs in runsDir: {child, url}. */
function startServer(kimpExe, runsDir) {
  return new Promise((resolve, reject) => {
    const child = spawn(kimpExe, ['gui', '--port', '0', '--runs-dir', runsDir], { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    child.stdout.on('data', (d) => {
      out += d;
      const m = /(http:\/\/127\.0\.0\.1:\d+\/)/.exec(out);
      if (m) resolve({ child: child, url: m[1] });
    });
    child.on('exit', (code) => reject(new Error(`kimp gui exited with ${code}: ${out}`)));
  });
}

/** Set the input `selector` to `value` and fire its change event (bubbling if `bubbles`). */
async function setInput(page, selector, value, bubbles = false) {
  await page.$eval(
    selector,
    (input, v, b) => {
      input.value = v;
      input.dispatchEvent(new Event('change', { bubbles: b }));
    },
    value,
    bubbles,
  );
}

/**
 * Set inputs of the Ground-motion tab in order (each change is one request to POST /api/motion)
 * and wait for the answer to the last one: the motion drawn has `samples` samples.
 */
async function setMotionInputs(page, inputs, samples) {
  for (const [selector, value] of inputs) await setInput(page, selector, value);
  await page.waitForFunction(
    (n) => Number(document.querySelector('#motion-info').dataset.samples) === n,
    { timeout: 15000 },
    samples,
  );
}

/** Set a text field of the scene form and fire its change event. */
async function setField(page, fieldPath, value) {
  await setInput(
    page,
    `#scene-form [data-path="${fieldPath}"] input, #scene-form input[data-path="${fieldPath}"]`,
    value,
    true,
  );
}

/**
 * Click `button`, then wait up to `timeout` ms for the status element `status` to show a new run
 * that is done, with `result` (a selector) in the results; returns the run's id (the status text
 * before ':').
 */
async function runAndWait(page, { button, status, result, timeout }) {
  const before = await page.$eval(status, (s) => s.textContent);
  await page.click(button);
  await page.waitForFunction(
    (statusSelector, prev, resultSelector) => {
      const s = document.querySelector(statusSelector);
      return s.textContent !== prev && s.dataset.state === 'done' && document.querySelector(resultSelector);
    },
    { timeout },
    status,
    before,
    result,
  );
  return page.$eval(status, (s) => s.textContent.split(':')[0]);
}

/**
 * `kimp gui` with its runs in ARTEFACTS/runs (emptied first) and a page of it in Chromium, ready
 * (downloads to ARTEFACTS/downloads, emptied first, if given): runs `test({ page, log, url,
 * runsDir, downloadDir })`, then checks that the page logged no console error. The browser and the server are
 * stopped whatever happens.
 */
async function withGuiPage(kimpExe, artefacts, { runs, downloads }, test) {
  const runsDir = path.join(artefacts, runs);
  fs.rmSync(runsDir, { recursive: true, force: true });
  fs.mkdirSync(artefacts, { recursive: true });
  const { child, url } = await startServer(kimpExe, runsDir);
  const browser = await launch();
  try {
    let downloadDir;
    if (downloads) {
      downloadDir = path.join(artefacts, downloads);
      fs.rmSync(downloadDir, { recursive: true, force: true });
    }
    const { page, log } = await watchedPage(browser, downloadDir);
    await page.goto(url, { waitUntil: 'load' });
    await page.waitForSelector('body[data-ready="1"]', { timeout: 15000 });
    await test({ page, log, url, runsDir, downloadDir });
    check(log.errors.length === 0, `no console error (${log.errors.join(' | ') || 'none'})`);
  } finally {
    await browser.close();
    child.kill('SIGTERM');
  }
}

/** Runs the async `main`; an error it throws is printed and ends the process with exit 1. */
function runMain(main) {
  main().catch((e) => {
    console.error(e);
    process.exit(1);
  });
}

module.exports = {
  launch,
  watchedPage,
  waitForFile,
  check,
  startServer,
  setInput,
  setMotionInputs,
  setField,
  runAndWait,
  withGuiPage,
  runMain,
};
