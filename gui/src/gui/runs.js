// kimp gui: background runs (start, progress by server-sent events, cancel, the list of runs), and
// their results, warnings and overlays.
'use strict';

(function () {
  const { state, getJson, postJson, showTab, clearErrors, showError } = kimpGui;
  const el = kimp.el;

  // ---- runs --------------------------------------------------------------------------------
  async function startRun(command, scene, sweep) {
    clearErrors();
    let id;
    try {
      id = (await postJson('/api/runs', { command: command, scene: scene, sweep: sweep })).id;
    } catch (e) {
      showError(e.message);
      return null;
    }
    const bar = document.getElementById('run-progress');
    const status = document.getElementById('run-status');
    const log = document.getElementById('run-log');
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
          else if (s.error) showError(s.error);
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

  async function openResults(id, overlay) {
    const data = await getJson(`/api/runs/${id}/data`);
    data.title = id;
    const others = [];
    for (const o of overlay || []) {
      const d = await getJson(`/api/runs/${o}/data`);
      d.title = o;
      others.push(d);
    }
    const pane = document.getElementById('results');
    state.shown = { id: id, overlay: overlay || [] };
    kimp.showResults(pane, data, others);
    pane.insertBefore(
      el('p', {}, [el('a', { href: `/api/runs/${id}/report`, download: `${id}.html`, text: 'download report.html' })]),
      pane.children[1],
    );
    showTab('results');
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
      return el('label', {}, [box, document.createTextNode(' ' + r.id)]);
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

  async function refreshRuns() {
    const list = await getJson('/api/runs');
    const host = document.getElementById('runs-list');
    host.innerHTML = '';
    const t = el('table', { class: 'data' });
    t.appendChild(
      el(
        'tr',
        {},
        ['run', 'command', 'state', ''].map((h) => el('th', { text: h })),
      ),
    );
    for (const r of list) {
      const actions = el('span');
      if (r.state === 'done') actions.appendChild(el('button', { text: 'results', onclick: () => openResults(r.id) }));
      if (r.state === 'running' || r.state === 'queued')
        actions.appendChild(
          el('button', { text: 'cancel', onclick: () => postJson(`/api/runs/${r.id}/cancel`, {}).then(refreshRuns) }),
        );
      // A cancelled or failed run: why, and what it wrote before it stopped.
      if (r.state !== 'done') {
        for (const f of (r.files || []).filter((x) => !x.endsWith('/')))
          actions.appendChild(el('a', { href: `/api/files/${r.id}/${f}`, text: f.slice(4) + ' ' }));
      }
      t.appendChild(
        el('tr', {}, [
          el('td', { text: r.id }),
          el('td', { text: r.command || '' }),
          el('td', { text: r.state + (r.state !== 'done' && r.error ? ` (${r.error})` : '') }),
          el('td', {}, [actions]),
        ]),
      );
    }
    host.appendChild(t);
  }

  Object.assign(kimpGui, { startRun, refreshRuns });
})();
