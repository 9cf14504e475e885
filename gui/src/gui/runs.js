// kimp gui: background runs (start, progress by server-sent events, cancel, the list of runs), and
// their results, warnings and overlays.
'use strict';

(function () {
  const { state, getJson, postJson, showTab, clearErrors, showError, saveSession } = kimpGui;
  const el = kimp.el;

  // ---- runs --------------------------------------------------------------------------------
  /**
   * Start a run named `opts.name` with `opts.notes`; its progress, log and error go to the
   * elements of `opts.prefix` ("run": the Scene tab's, "param": the Parametric tab's).
   */
  async function startRun(command, scene, sweep, opts) {
    const o = opts || {};
    const prefix = o.prefix || 'run';
    const report = (message) => {
      if (prefix === 'run') showError(message);
      else document.getElementById(prefix + '-error').textContent = message;
    };
    if (prefix === 'run') clearErrors();
    else document.getElementById(prefix + '-error').textContent = '';
    let id;
    try {
      id = (
        await postJson('/api/runs', {
          command: command,
          scene: scene,
          sweep: sweep,
          name: o.name || '',
          notes: o.notes || '',
        })
      ).id;
    } catch (e) {
      report(e.message);
      return null;
    }
    const bar = document.getElementById(prefix + '-progress');
    const status = document.getElementById(prefix + '-status');
    const log = document.getElementById(prefix + '-log');
    log.textContent = '';
    status.textContent = `${id}: running`;
    status.dataset.state = 'running';
    bar.value = 0;
    state.current = id;
    return new Promise((resolve) => {
      const events = new EventSource(`/api/runs/${id}/events`);
      events.onmessage = async (m) => {
        const s = JSON.parse(m.data);
        bar.value = s.progress || 0;
        for (const line of s.log || []) log.textContent += line + '\n';
        log.scrollTop = log.scrollHeight;
        let note = '';
        if (s.state === 'queued') note = ` (place ${s.queue_position} in the queue)`;
        else if (s.state === 'running' && s.progress_text) note = ` (${s.progress_text})`;
        status.textContent = `${id}: ${s.state}${note}`;
        status.dataset.state = s.state;
        if (s.state !== 'running' && s.state !== 'queued') {
          events.close();
          if (s.state === 'done') await openResults(id);
          else if (s.error) report(s.error);
          resolve(s.state);
        }
      };
      events.onerror = () => {
        events.close();
        resolve('lost');
      };
    });
  }

  /** The run's warnings (its log's "warning:" lines), e.g. why a sweep wrote no d_SRSS table. */
  async function runWarnings(id) {
    const r = await fetch(`/api/files/${id}/run.log`);
    if (!r.ok) return [];
    return (await r.text())
      .split('\n')
      .filter((l) => l.startsWith('warning: '))
      .map((l) => l.slice(9));
  }

  /** A run's label: its name, else its id. */
  const runLabel = (r) => (r && r.name ? r.name : r ? r.id : '');

  /** The next frame painted: what changed on the page before is shown before a long task runs. */
  const painted = () => new Promise((resolve) => requestAnimationFrame(() => setTimeout(resolve, 0)));
  const megabytes = (bytes) => (bytes / 1e6).toFixed(1);

  /**
   * The progress of opening results in `pane`: a spinner, a progress bar and a line ("loading the
   * results of NAME: 3.2 of 17.1 MB", role status), the pane aria-busy until done() or fail().
   */
  function loadingIndicator(pane, id) {
    const bar = el('progress', { class: 'loading-bar' });
    const line = el('span', { class: 'loading-text', text: `opening the results of ${id}…` });
    pane.innerHTML = '';
    pane.setAttribute('aria-busy', 'true');
    delete pane.dataset.loaded;
    pane.appendChild(
      el('div', { class: 'results-loading', role: 'status', 'aria-live': 'polite' }, [
        el('span', { class: 'spinner', 'aria-hidden': 'true' }),
        line,
        bar,
      ]),
    );
    return {
      say: (text) => {
        line.textContent = text;
      },
      bytes: (label, received, total) => {
        const known = total >= received;
        line.textContent = `loading the results of ${label}: ${megabytes(received)}${
          known ? ` of ${megabytes(total)}` : ''
        } MB`;
        if (known) {
          bar.max = total;
          bar.value = received;
        }
      },
      done: (id) => {
        pane.setAttribute('aria-busy', 'false');
        pane.dataset.loaded = id;
      },
      fail: (message) => {
        pane.setAttribute('aria-busy', 'false');
        pane.innerHTML = '';
        pane.appendChild(el('div', { class: 'run-error', text: message }));
      },
    };
  }

  /**
   * GET `url` (a run's results) as JSON, its bytes counted in `loading` against their
   * Content-Length as they arrive (the server sends results uncompressed, their size known), then
   * parsed once the indicator says so on screen.
   */
  async function loadResults(url, label, loading) {
    loading.say(`loading the results of ${label}: kimp reads the results files…`);
    const r = await fetch(url);
    if (!r.ok) throw new Error((await r.json().catch(() => ({}))).error || r.statusText);
    const total = Number(r.headers.get('Content-Length')) || 0;
    const chunks = [];
    let received = 0;
    const reader = r.body.getReader();
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      chunks.push(value);
      received += value.length;
      loading.bytes(label, received, total);
    }
    loading.say(`reading the ${megabytes(received)} MB of results of ${label}…`);
    await painted();
    const bytes = new Uint8Array(received);
    let at = 0;
    for (const c of chunks) {
      bytes.set(c, at);
      at += c.length;
    }
    return JSON.parse(new TextDecoder().decode(bytes));
  }

  let opening = 0;

  /**
   * Show the results of run `id` (with the runs `overlay` on its charts) in the Results tab, a
   * progress indicator there until its charts are drawn (then #results has data-loaded = id).
   */
  async function openResults(id, overlay) {
    const ticket = ++opening;
    const pane = document.getElementById('results');
    const loading = loadingIndicator(pane, id);
    showTab('results');
    const load = async (runId) => {
      const run = await getJson(`/api/runs/${runId}`);
      const data = await loadResults(`/api/runs/${runId}/data`, runLabel(run), loading);
      data.title = runLabel(run);
      return { run, data };
    };
    let shown;
    const others = [];
    try {
      shown = await load(id);
      for (const o of overlay || []) others.push((await load(o)).data);
      loading.say('drawing the charts…');
      await painted();
    } catch (e) {
      if (ticket === opening) loading.fail(`results of ${id}: ${e.message}`);
      throw e;
    }
    // Another run was opened meanwhile: it is the one shown.
    if (ticket !== opening) return;
    const { run, data } = shown;
    state.shown = { id: id, overlay: overlay || [] };
    kimp.showResults(pane, data, others);
    pane.insertBefore(
      el('p', {}, [el('a', { href: `/api/runs/${id}/report`, download: `${id}.html`, text: 'download report.html' })]),
      pane.children[1],
    );
    if (run.notes) pane.insertBefore(el('p', { class: 'run-notes-shown', text: run.notes }), pane.children[1]);
    saveSession();
    await painted();
    if (ticket !== opening) return;
    loading.done(id);
    await Promise.all([runPicker(id, data, overlay || []), showRunNotes(id, data)]);
  }

  async function showRunNotes(id, data) {
    const host = document.getElementById('results-notes');
    host.innerHTML = '';
    const warnings = await runWarnings(id);
    const csv = data.csv || {};
    const gapStudy = data.kind === 'sweep' && Object.keys(csv).includes('sweep.csv') && !csv['dsrss_table.csv'];
    const dsrss = warnings.filter((w) => /d_SRSS/.test(w));
    if (gapStudy && dsrss.length) {
      host.appendChild(
        el('div', { class: 'notice dsrss-missing', text: `No d_req / d_SRSS table: ${dsrss.join('\n')}` }),
      );
    }
    const rest = warnings.filter((w) => !dsrss.includes(w));
    if (rest.length)
      host.appendChild(el('div', { class: 'notice run-warnings', text: `warnings of ${id}:\n${rest.join('\n')}` }));
  }

  /** Other finished runs of the same command to overlay on the charts (legend: run: case). */
  async function runPicker(id, data, overlay) {
    const host = document.getElementById('results-bar');
    host.innerHTML = '';
    const list = (await getJson('/api/runs')).filter(
      (r) => r.state === 'done' && r.id !== id && r.command === data.kind,
    );
    if (!list.length) return;
    const boxes = list.map((r) => {
      const box = el('input', { type: 'checkbox', value: r.id, class: 'overlay-run' });
      box.checked = overlay.includes(r.id);
      return el('label', { title: r.id }, [box, document.createTextNode(' ' + runLabel(r))]);
    });
    const go = el('button', { class: 'overlay-apply', text: 'Overlay on the charts' });
    go.addEventListener('click', () => {
      const chosen = Array.from(host.querySelectorAll('.overlay-run:checked')).map((b) => b.value);
      openResults(id, chosen);
    });
    host.appendChild(
      el('div', { class: 'section run-picker' }, [
        el('strong', { text: `Overlay other ${data.kind} runs:` }),
        ...boxes,
        go,
      ]),
    );
  }

  /** Reopen a run's scene in the editor (a sweep: its base scene and its sweep file). */
  async function editRun(listed) {
    // The run as it is now (renamed since the list was drawn, perhaps).
    const r = await getJson(`/api/runs/${listed.id}`);
    const text = async (f) => {
      const res = await fetch(`/api/files/${r.id}/${f}`);
      if (!res.ok) throw new Error(`${r.id}/${f}: ${res.statusText}`);
      return res.text();
    };
    const scene = await text('scene.yaml');
    if (r.command === 'sweep') {
      await kimpGui.openScene('lumped', scene);
      document.getElementById('sweep-yaml').value = await text('sweep.yaml');
    } else await kimpGui.openScene(r.command, scene);
    document.getElementById('run-name').value = r.name || '';
    document.getElementById('run-notes').value = r.notes || '';
    showTab(r.command === 'sweep' ? 'parametric' : 'scene');
    saveSession();
  }

  async function refreshRuns() {
    const list = await getJson('/api/runs');
    const host = document.getElementById('runs-list');
    // Not while the user types a name or notes in the table.
    if (host.contains(document.activeElement) && document.activeElement.tagName === 'INPUT') return;
    host.innerHTML = '';
    const t = el('table', { class: 'data runs' });
    t.appendChild(
      el(
        'tr',
        {},
        ['name', 'notes', 'run', 'command', 'state', ''].map((h) => el('th', { text: h })),
      ),
    );
    for (const r of list) {
      const actions = el('span');
      if (r.state === 'done') actions.appendChild(el('button', { text: 'results', onclick: () => openResults(r.id) }));
      actions.appendChild(el('button', { class: 'run-edit', text: 'edit', onclick: () => editRun(r) }));
      if (r.state === 'running' || r.state === 'queued')
        actions.appendChild(
          el('button', { text: 'cancel', onclick: () => postJson(`/api/runs/${r.id}/cancel`, {}).then(refreshRuns) }),
        );
      else
        actions.appendChild(
          el('button', {
            class: 'run-delete',
            text: 'delete',
            onclick: () => postJson(`/api/runs/${r.id}/delete`, {}).then(refreshRuns),
          }),
        );
      // A cancelled or failed run: why, and what it wrote before it stopped.
      if (r.state !== 'done') {
        for (const f of (r.files || []).filter((x) => !x.endsWith('/')))
          actions.appendChild(el('a', { href: `/api/files/${r.id}/${f}`, text: f.slice(4) + ' ' }));
      }
      const name = el('input', { type: 'text', class: 'run-name', value: r.name || '', placeholder: r.id });
      const notes = el('input', { type: 'text', class: 'run-notes', value: r.notes || '' });
      const save = () => postJson(`/api/runs/${r.id}/meta`, { name: name.value, notes: notes.value });
      name.addEventListener('change', save);
      notes.addEventListener('change', save);
      t.appendChild(
        el('tr', { 'data-id': r.id }, [
          el('td', {}, [name]),
          el('td', {}, [notes]),
          el('td', { text: r.id }),
          el('td', { text: r.command || '' }),
          el('td', { class: 'run-state', text: r.state + (r.state !== 'done' && r.error ? ` (${r.error})` : '') }),
          el('td', {}, [actions]),
        ]),
      );
    }
    host.appendChild(t);
  }

  // The Runs tab follows the runs by itself (every 2 s while it is shown).
  setInterval(() => {
    if (document.getElementById('pane-runs').classList.contains('active')) refreshRuns().catch(() => {});
  }, 2000);

  Object.assign(kimpGui, { startRun, refreshRuns, openResults });
})();
