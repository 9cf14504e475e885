// kimp gui: the Ground-motion tab: the synthetic motion, a PEER record or an uploaded file, with
// the scene's scaling, charts of acceleration, velocity and displacement.
'use strict';

(function () {
  const { state, getJson, fields, sceneYaml, syncYaml } = kimpGui;
  const el = kimp.el;

  // ---- ground motion -----------------------------------------------------------------------
  // The chosen record as the server read it (unscaled, m/s²); the scene's scaling is applied here
  // exactly as a run applies it (scale_to_pga, then scale, then trim to round(duration / dt)).
  const motion = { rec: null, file: null, serial: 0 };
  const TWO_COLUMN_UNITS = { g: 9.80665, 'm/s^2': 1, 'cm/s^2': 0.01 };
  const MOTION_KEYS = [
    ['motion-scale-to-pga', 'ground_motion.scale_to_pga'],
    ['motion-scale', 'ground_motion.scale'],
    ['motion-duration', 'ground_motion.duration'],
  ];

  function sceneInput(path) {
    return document.querySelector(`#scene-form input[data-path="${path}"], #scene-form select[data-path="${path}"]`);
  }

  function sceneField(path) {
    return fields.find((f) => f.key.path === path);
  }

  function setSceneValue(path, value) {
    const input = sceneInput(path);
    if (input) {
      input.value = value;
      syncYaml();
    }
  }

  /**
   * Starts a motion request: the returned function tells whether it is still the latest, so that
   * a slow answer (the synthetic motion, a record) never replaces the one chosen after it.
   */
  function motionRequest() {
    const serial = ++motion.serial;
    return () => serial === motion.serial;
  }

  function integrate(a, dt) {
    const v = [0];
    for (let i = 1; i < a.length; ++i) v.push(v[i - 1] + 0.5 * (a[i - 1] + a[i]) * dt);
    return v;
  }

  /** The motion as a run would see it: [acceleration (m/s²), description of the scaling]. */
  function scaledMotion(rec) {
    const text = (path) => (sceneInput(path) ? sceneInput(path).value.trim() : '');
    const unitOf = (path) => (sceneField(path) ? sceneField(path).key.unit || '' : '');
    let a = rec.acceleration.slice();
    const peak = (xs) => xs.reduce((m, x) => Math.max(m, Math.abs(x)), 0);
    const notes = [];
    const toPga = text('ground_motion.scale_to_pga');
    if (toPga) {
      const target = kimp.parseQuantity(toPga, unitOf('ground_motion.scale_to_pga'));
      const factor = target / peak(a);
      a = a.map((x) => Math.max(-target, Math.min(target, x * factor)));
      notes.push(`scaled to PGA ${toPga} (×${kimp.fmt(factor, 4)})`);
    }
    const scaleText = text('ground_motion.scale');
    if (scaleText) {
      const scale = kimp.parseQuantity(scaleText, unitOf('ground_motion.scale'));
      a = a.map((x) => x * scale);
      notes.push(`scale ${kimp.fmt(scale, 6)}`);
    }
    const durationText = text('ground_motion.duration');
    if (durationText) {
      const duration = kimp.parseQuantity(durationText, unitOf('ground_motion.duration'));
      a = a.slice(0, Math.min(a.length, Math.round(duration / rec.dt)));
      notes.push(`trimmed to ${kimp.fmt(duration, 6)} s`);
    }
    return [a, notes.length ? notes.join(', ') : 'unscaled'];
  }

  function peakAt(xs) {
    let k = 0;
    for (let i = 1; i < xs.length; ++i) if (Math.abs(xs[i]) > Math.abs(xs[k])) k = i;
    return k;
  }

  function plotMotion() {
    const host = document.getElementById('motion-charts');
    const info = document.getElementById('motion-info');
    const out = document.getElementById('motion-error');
    host.innerHTML = '';
    info.textContent = '';
    out.textContent = '';
    const rec = motion.rec;
    if (!rec) return;
    let a;
    let notes;
    try {
      [a, notes] = rec.scaled ? [rec.acceleration, 'as the run scales it'] : scaledMotion(rec);
    } catch (e) {
      out.textContent = `ground motion: ${e.message}`;
      return;
    }
    const t = a.map((_, i) => i * rec.dt);
    const v = integrate(a, rec.dt);
    const d = integrate(v, rec.dt);
    const [ia, iv, id] = [peakAt(a), peakAt(v), peakAt(d)];
    const pga = Math.abs(a[ia]) / 9.80665;
    const pgv = Math.abs(v[iv]) * 100;
    const pgd = Math.abs(d[id]) * 100;
    info.dataset.pga = String(pga);
    info.dataset.samples = String(a.length);
    info.textContent =
      `${rec.name}: dt = ${rec.dt} s, ${a.length} samples (${kimp.fmt(a.length * rec.dt, 6)} s), ` +
      `PGA = ${kimp.fmt(pga, 4)} g, PGV = ${kimp.fmt(pgv, 4)} cm/s, PGD = ${kimp.fmt(pgd, 4)} cm (${notes})`;
    const marker = (i, ys, label) => {
      const y = new Array(ys.length).fill(null);
      y[i] = ys[i];
      return { label: label, y: y, marker: true, color: '#d62728' };
    };
    kimp.chart(host, {
      title: `${rec.name}: ground acceleration, PGA = ${kimp.fmt(pga, 4)} g at ${kimp.fmt(t[ia], 4)} s`,
      xlabel: 'time (s)',
      ylabel: 'acceleration (m/s²)',
      x: t,
      height: 260,
      series: [{ label: 'a_g', y: a }, marker(ia, a, `PGA ${kimp.fmt(pga, 4)} g`)],
    });
    kimp.chart(host, {
      title: `${rec.name}: ground velocity, PGV = ${kimp.fmt(pgv, 4)} cm/s at ${kimp.fmt(t[iv], 4)} s`,
      xlabel: 'time (s)',
      ylabel: 'velocity (cm/s)',
      x: t,
      height: 260,
      series: [
        { label: 'v_g', y: v.map((x) => x * 100) },
        marker(
          iv,
          v.map((x) => x * 100),
          `PGV ${kimp.fmt(pgv, 4)} cm/s`,
        ),
      ],
    });
    kimp.chart(host, {
      title: `${rec.name}: ground displacement, PGD = ${kimp.fmt(pgd, 4)} cm at ${kimp.fmt(t[id], 4)} s`,
      xlabel: 'time (s)',
      ylabel: 'displacement (cm)',
      x: t,
      height: 260,
      series: [
        { label: 'd_g', y: d.map((x) => x * 100) },
        marker(
          id,
          d.map((x) => x * 100),
          `PGD ${kimp.fmt(pgd, 4)} cm`,
        ),
      ],
    });
  }

  /**
   * The synthetic motion is generated by kimp at run time: the page asks the server for it
   * (scaled as the run scales it) and draws nothing of its own when the server cannot.
   */
  async function loadSynthetic() {
    const latest = motionRequest();
    motion.rec = null;
    if (!state.info.motion_preview) {
      document.getElementById('motion-charts').innerHTML = '';
      document.getElementById('motion-info').textContent =
        'The synthetic near-fault motion is generated by kimp at ' +
        'run time (ground_motion.synthetic); this kimp gui cannot draw it before a run.';
      return;
    }
    const r = await fetch('/api/motion', {
      method: 'POST',
      headers: { 'Content-Type': 'application/json', 'X-Kimp-Request': '1' },
      body: JSON.stringify({ command: state.command === 'sweep' ? 'lumped' : state.command, scene: sceneYaml() }),
    });
    const body = await r.json();
    if (!latest()) return;
    if (r.ok) {
      motion.rec = Object.assign(body, { scaled: true });
      plotMotion();
    } else {
      const info = document.getElementById('motion-info');
      document.getElementById('motion-charts').innerHTML = '';
      info.textContent = '';
      delete info.dataset.pga;
      delete info.dataset.samples;
      document.getElementById('motion-error').textContent = body.error;
    }
  }

  async function uploadMotion() {
    const latest = motionRequest();
    const file = motion.file;
    const unit = document.getElementById('motion-unit').value;
    const at2 = /\.at2$/i.test(file.name);
    const r = await fetch('/api/upload?name=' + encodeURIComponent(file.name) + '&unit=' + TWO_COLUMN_UNITS[unit], {
      method: 'POST',
      headers: { 'X-Kimp-Request': '1', 'Content-Type': 'application/octet-stream' },
      body: await file.text(),
    });
    const body = await r.json();
    if (!latest()) return;
    document.getElementById('motion-error').textContent = r.ok ? '' : body.error;
    if (!r.ok) return;
    // The scene names the uploaded file and, for a two-column file, the unit of its column.
    setSceneValue('ground_motion.record', body.path);
    setSceneValue('ground_motion.record_unit', at2 ? '' : unit);
    motion.rec = body;
    motion.key = body.path;
    const pick = document.getElementById('motion-record');
    let option = pick.querySelector('option[data-upload]');
    if (!option) {
      option = el('option', { 'data-upload': '1' });
      pick.appendChild(option);
    }
    option.value = body.path;
    option.textContent = `uploaded: ${file.name}${at2 ? '' : ' (' + unit + ')'}`;
    pick.value = body.path;
    plotMotion();
  }

  /** The motion tab's scaling inputs mirror the scene's keys (both ways). */
  function syncMotionInputs() {
    for (const [id, path] of MOTION_KEYS) {
      const input = sceneInput(path);
      document.getElementById(id).value = input ? input.value : '';
    }
  }

  async function showMotion() {
    syncMotionInputs();
    const record = sceneInput('ground_motion.record') ? sceneInput('ground_motion.record').value.trim() : '';
    if (!record || record === 'synthetic') {
      document.getElementById('motion-record').value = 'synthetic';
      await loadSynthetic();
      return;
    }
    const pick = document.getElementById('motion-record');
    if ((!motion.rec || motion.key !== record) && Array.from(pick.options).some((o) => o.value === record)) {
      pick.value = record;
      const latest = motionRequest();
      const rec = await getJson('/api/records/' + encodeURIComponent(record));
      if (!latest()) return;
      motion.rec = rec;
      motion.key = record;
    }
    plotMotion();
  }

  async function initMotion() {
    const pick = document.getElementById('motion-record');
    pick.appendChild(
      el('option', { value: 'synthetic', text: 'synthetic near-fault motion (ground_motion.synthetic)' }),
    );
    for (const name of await getJson('/api/records')) pick.appendChild(el('option', { value: name, text: name }));
    pick.addEventListener('change', async () => {
      if (pick.selectedOptions[0] && pick.selectedOptions[0].dataset.upload) return;
      motion.file = null;
      setSceneValue('ground_motion.record', pick.value === 'synthetic' ? '' : pick.value);
      setSceneValue('ground_motion.record_unit', '');
      if (pick.value === 'synthetic') await loadSynthetic();
      else {
        const latest = motionRequest();
        const rec = await getJson('/api/records/' + encodeURIComponent(pick.value));
        if (!latest()) return;
        motion.rec = rec;
        motion.key = pick.value;
        plotMotion();
      }
    });
    document.getElementById('motion-upload').addEventListener('change', async (e) => {
      motion.file = e.target.files[0] || null;
      if (motion.file) await uploadMotion();
    });
    document.getElementById('motion-unit').addEventListener('change', async () => {
      if (motion.file && !/\.at2$/i.test(motion.file.name)) await uploadMotion();
    });
    for (const [id, path] of MOTION_KEYS) {
      document.getElementById(id).addEventListener('change', async (e) => {
        setSceneValue(path, e.target.value.trim());
        if (motion.rec && !motion.rec.scaled) plotMotion();
        else await showMotion();
      });
    }
  }

  Object.assign(kimpGui, { showMotion, initMotion });
})();
