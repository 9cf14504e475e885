// kimp gui: the Ground-motion tab: the synthetic motion, a PEER record or an uploaded file, with
// the scene's scaling, charts of acceleration, velocity and displacement.
'use strict';

(function () {
  const { state, getJson, postJson, sceneYaml, syncYaml } = kimpGui;
  const el = kimp.el;

  // ---- ground motion -----------------------------------------------------------------------
  // The scene's ground motion as the server loaded, scaled and trimmed it for the scene's run
  // (POST /api/motion, m/s²), the uploaded file and the serial of the latest request.
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

  function peakAt(xs) {
    let k = 0;
    for (let i = 1; i < xs.length; ++i) if (Math.abs(xs[i]) > Math.abs(xs[k])) k = i;
    return k;
  }

  /**
   * The pseudo-acceleration response spectrum Sa(T) = ω² max|u| of the record `a` (m/s², step
   * `dt`) at `periods` (s) for the damping ratio `zeta`: each linear SDOF ü + 2ζωu̇ + ω²u = −a_g
   * stepped by the exact recurrence for a linearly interpolated excitation (Nigam and Jennings;
   * Chopra, Dynamics of Structures, §5.2), so any dt is exact.
   */
  function responseSpectrum(a, dt, periods, zeta) {
    const root = Math.sqrt(1 - zeta * zeta);
    return periods.map((T) => {
      const w = (2 * Math.PI) / T;
      const wd = w * root;
      const k = w * w;
      const e = Math.exp(-zeta * w * dt);
      const s = Math.sin(wd * dt);
      const c = Math.cos(wd * dt);
      const A = e * ((zeta / root) * s + c);
      const B = e * (s / wd);
      const z = (2 * zeta) / (w * dt);
      const C = (z + e * (((1 - 2 * zeta * zeta) / (wd * dt) - zeta / root) * s - (1 + z) * c)) / k;
      const D = (1 - z + e * (((2 * zeta * zeta - 1) / (wd * dt)) * s + z * c)) / k;
      const A1 = -e * (w / root) * s;
      const B1 = e * (c - (zeta / root) * s);
      const C1 = (-1 / dt + e * ((w / root + zeta / (dt * root)) * s + c / dt)) / k;
      const D1 = (1 - e * ((zeta / root) * s + c)) / (k * dt);
      let u = 0;
      let v = 0;
      let peak = 0;
      for (let i = 0; i + 1 < a.length; ++i) {
        const p0 = -a[i];
        const p1 = -a[i + 1];
        const u1 = A * u + B * v + C * p0 + D * p1;
        v = A1 * u + B1 * v + C1 * p0 + D1 * p1;
        u = u1;
        if (Math.abs(u) > peak) peak = Math.abs(u);
      }
      return k * peak;
    });
  }

  /** The spectrum chart (5 % damping, Sa in g) with the isolated period of the scene's model marked. */
  async function plotSpectrum(host, rec) {
    const ZETA = 0.05;
    const periods = [];
    for (let i = 0; i <= 120; ++i) periods.push(0.02 * Math.pow(6 / 0.02, i / 120));
    let mark = null;
    if (state.command === 'lumped') {
      try {
        const scene = sceneYaml();
        const valid = await postJson('/api/validate', { command: 'lumped', scene: scene });
        const m = valid.ok ? await postJson('/api/preview', { command: 'lumped', scene: scene }) : {};
        if (m.isolated_period) mark = { T: m.isolated_period, basis: m.isolated_period_basis };
      } catch {
        // An invalid scene: the spectrum without a marker (the Scene tab says why).
      }
    }
    if (mark && !periods.includes(mark.T)) periods.push(mark.T);
    periods.sort((x, y) => x - y);
    const sa = responseSpectrum(rec.acceleration, rec.dt, periods, ZETA).map((x) => x / 9.80665);
    const series = [{ label: 'Sa (5 % damping)', y: sa }];
    let title = `${rec.name}: pseudo-acceleration response spectrum, 5 % damping`;
    if (mark) {
      const i = periods.indexOf(mark.T);
      const y = new Array(periods.length).fill(null);
      y[i] = sa[i];
      series.push({ label: `isolated period ${kimp.fmt(mark.T, 3)} s`, y: y, marker: true, color: '#d62728' });
      title += `; isolated period T = ${kimp.fmt(mark.T, 3)} s (${mark.basis}): Sa = ${kimp.fmt(sa[i], 4)} g`;
      host.dataset.isolatedPeriod = String(mark.T);
      host.dataset.saAtPeriod = String(sa[i] * 9.80665);
    }
    const c = kimp.chart(host, {
      title: title,
      xlabel: 'period T (s)',
      ylabel: 'Sa (g)',
      x: periods,
      height: 260,
      series: series,
    });
    c.card.classList.add('spectrum');
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
    const a = rec.acceleration;
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
      `PGA = ${kimp.fmt(pga, 4)} g, PGV = ${kimp.fmt(pgv, 4)} cm/s, PGD = ${kimp.fmt(pgd, 4)} cm ` +
      '(as the run scales it)';
    const marker = (i, ys, label) => {
      const y = new Array(ys.length).fill(null);
      y[i] = ys[i];
      return { label: label, y: y, marker: true, color: '#d62728' };
    };
    const cm = (xs) => xs.map((x) => x * 100);
    for (const [what, ys, ylabel, symbol, peak, i, value] of [
      ['acceleration', a, 'acceleration (m/s²)', 'a_g', 'PGA', ia, `${kimp.fmt(pga, 4)} g`],
      ['velocity', cm(v), 'velocity (cm/s)', 'v_g', 'PGV', iv, `${kimp.fmt(pgv, 4)} cm/s`],
      ['displacement', cm(d), 'displacement (cm)', 'd_g', 'PGD', id, `${kimp.fmt(pgd, 4)} cm`],
    ]) {
      kimp.chart(host, {
        title: `${rec.name}: ground ${what}, ${peak} = ${value} at ${kimp.fmt(t[i], 4)} s`,
        xlabel: 'time (s)',
        ylabel: ylabel,
        x: t,
        height: 260,
        series: [{ label: symbol, y: ys }, marker(i, ys, `${peak} ${value}`)],
      });
    }
    const spectrum = el('div', { class: 'spectrum-host' });
    host.appendChild(spectrum);
    return plotSpectrum(spectrum, rec);
  }

  /**
   * The scene's ground motion (a record, an upload or the synthetic motion) is loaded, scaled and
   * trimmed by kimp as its run does: the page asks the server for it and draws nothing of its own
   * when the server cannot.
   */
  async function loadMotion() {
    const latest = motionRequest();
    motion.rec = null;
    if (!state.info.motion_preview) {
      document.getElementById('motion-charts').innerHTML = '';
      document.getElementById('motion-info').textContent =
        'The ground motion is loaded, scaled and trimmed (the synthetic near-fault motion generated) ' +
        'by kimp at run time; this kimp gui cannot draw it before a run.';
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
      motion.rec = body;
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
    const pick = document.getElementById('motion-record');
    let option = pick.querySelector('option[data-upload]');
    if (!option) {
      option = el('option', { 'data-upload': '1' });
      pick.appendChild(option);
    }
    option.value = body.path;
    option.textContent = `uploaded: ${file.name}${at2 ? '' : ' (' + unit + ')'}`;
    pick.value = body.path;
    await loadMotion();
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
    const pick = document.getElementById('motion-record');
    if (!record || record === 'synthetic') pick.value = 'synthetic';
    else if (Array.from(pick.options).some((o) => o.value === record)) pick.value = record;
    await loadMotion();
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
      await loadMotion();
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
        await loadMotion();
      });
    }
  }

  Object.assign(kimpGui, { showMotion, initMotion });
})();
