// kimp results page: the building animation of a lumped run (floors, isolator, walls, neighbours,
// impact flashes) with play/pause/restart, speed, scrubbing and SVG frame export.
'use strict';

(function () {
  const { el, fmt, download, escapeXml, setTimeCursor } = kimp;

  // ---- animation -------------------------------------------------------------------------------
  /**
   * The player of an animation, appended to `parent`: a row of controls (`o.leading` ones first,
   * then play, restart, speed, exaggeration, frame export and a time label), a scrub bar and the
   * SVG canvas of o.width x o.height. Classes are `${o.prefix}-play` etc.; `frameSvg()` is the
   * frame shown as a standalone SVG document; `run(state, c)` plays it (below).
   */
  function makePlayer(parent, o) {
    const NS = 'http://www.w3.org/2000/svg';
    const cls = (name) => ({ class: `${o.prefix}-${name}` });
    const p = {
      play: el('button', { ...cls('play'), text: 'Play' }),
      restart: el('button', { ...cls('restart'), text: 'Restart' }),
      speed: el('select', cls('speed'), o.speeds.map((s) => el('option', { value: s, text: s + '×' }))),
      exaggeration: el('input', { type: 'number', min: 1, step: 1, ...o.exaggeration, ...cls('exaggeration') }),
      exportFrame: el('button', { ...cls('export'), text: 'Frame SVG' }),
      label: el('span', { ...o.label, ...cls('time') }),
      scrub: el('input', { type: 'range', min: 0, max: o.scrubMax, value: 0, ...cls('scrub') }),
      svg: document.createElementNS(NS, 'svg'),
    };
    p.speed.value = '1';
    parent.appendChild(
      el('div', { class: 'controls' }, [
        ...(o.leading || []),
        p.play,
        p.restart,
        el('label', { text: ' speed ' }, [p.speed]),
        el('label', { text: ' exaggeration ×' }, [p.exaggeration]),
        p.exportFrame,
        p.label,
      ]),
    );
    parent.appendChild(p.scrub);
    p.svg.setAttribute('viewBox', `0 0 ${o.width} ${o.height}`);
    p.svg.setAttribute('class', o.svgClass);
    p.svg.setAttribute('xmlns', NS);
    parent.appendChild(p.svg);
    p.frameSvg = () =>
      `<svg xmlns="${NS}" viewBox="0 0 ${o.width} ${o.height}" width="${o.width}" height="${o.height}" ` +
      'font-family="Helvetica, Arial, sans-serif">' +
      `<rect width="${o.width}" height="${o.height}" fill="#fff"/>${p.svg.innerHTML}</svg>`;
    /**
     * Play, pause and restart over the caller's `state.playing`: c.step(ms) moves the animation
     * on by ms of wall time, c.atEnd() says whether it is at its end, c.rewind() goes back to the
     * start, c.draw() shows the frame, c.onPlay() (optional) runs when playing starts. Wires the
     * Play and Restart buttons and returns {play, pause}.
     */
    p.run = (state, c) => {
      let last = null;
      function tick(now) {
        if (!state.playing) {
          last = null;
          return;
        }
        if (last !== null) c.step(now - last);
        last = now;
        if (c.atEnd()) {
          state.playing = false;
          p.play.textContent = 'Play';
        }
        c.draw();
        if (state.playing) requestAnimationFrame(tick);
      }
      const controls = {
        play: () => {
          if (state.playing) return;
          if (c.atEnd()) c.rewind();
          state.playing = true;
          if (c.onPlay) c.onPlay();
          p.play.textContent = 'Pause';
          requestAnimationFrame(tick);
        },
        pause: () => {
          state.playing = false;
          p.play.textContent = 'Play';
        },
      };
      p.play.addEventListener('click', () => (state.playing ? controls.pause() : controls.play()));
      p.restart.addEventListener('click', () => {
        c.rewind();
        c.draw();
        controls.play();
      });
      return controls;
    };
    return p;
  }

  /**
   * The views of a case's displacement history: canvas (px), SVG class, exaggeration at first and
   * the stem of an exported frame's file name (STEM_t<time>.svg).
   */
  const historyViews = {
    building: { width: 900, height: 420, svgClass: 'animation', exaggeration: 10, frameName: 'frame' },
    plan: { width: 900, height: 560, svgClass: 'animation plan-view', exaggeration: 20, frameName: 'plan_frame' },
  };

  /**
   * The player of a case's displacement history in historyViews[view]: makePlayer's controls as
   * 'anim-*' (speeds 0.1× to 5×, exaggeration up to 200, a scrub bar of 1000 steps). The frame at
   * state.t is the last history sample i at or before t; drawFrame(i, tText) returns its SVG
   * elements (tText: the sample's time to the digits its sampling needs, as the time label and the
   * exported frame's name show it). Returns {state, play, pause, seek, setCase, frameSvg}: nothing
   * is drawn until setCase(c) gives the case (state.kase).
   */
  function historyPlayer(parent, view, drawFrame) {
    const o = historyViews[view];
    const player = makePlayer(parent, {
      prefix: 'anim',
      width: o.width,
      height: o.height,
      svgClass: o.svgClass,
      speeds: [0.1, 0.25, 0.5, 1, 2, 5],
      exaggeration: { max: 200, value: o.exaggeration },
      label: { id: 'anim-time', text: 't = 0 s' },
      scrubMax: 1000,
    });
    const { speed, scrub, exportFrame } = player;
    const exag = player.exaggeration;
    const state = { t: 0, playing: false, speed: 1, exaggeration: o.exaggeration, frame: 0, kase: null };

    const times = () => state.kase.history.displacement.time;
    const tEnd = () => times()[times().length - 1];
    const frameAt = (t) => {
      const ts = times();
      let lo = 0;
      let hi = ts.length - 1;
      while (hi - lo > 1) {
        const mid = (lo + hi) >> 1;
        if (ts[mid] <= t) lo = mid;
        else hi = mid;
      }
      return ts[hi] <= t ? hi : lo;
    };
    // The drawn frame's own time (the history sample), to the digits its sampling needs.
    const frameTime = () => times()[state.frame];
    const timeText = (t) => {
      const ts = times();
      const dt = ts.length > 1 ? ts[1] - ts[0] : 0.01;
      return t.toFixed(Math.min(6, Math.max(2, Math.ceil(-Math.log10(dt) - 1e-9))));
    };

    function draw() {
      if (!state.kase) return;
      state.frame = frameAt(state.t);
      const tText = timeText(frameTime());
      player.svg.innerHTML = drawFrame(state.frame, tText);
      player.label.textContent = `t = ${tText} s`;
      scrub.value = String(Math.round((state.t / tEnd()) * 1000));
      setTimeCursor(state.t);
    }

    const { play, pause } = player.run(state, {
      step: (ms) => {
        state.t = Math.min(state.t + (ms / 1000) * state.speed, tEnd());
      },
      atEnd: () => state.t >= tEnd(),
      rewind: () => {
        state.t = 0;
      },
      draw: draw,
    });
    const api = {
      state: state,
      play: play,
      pause: pause,
      seek: (t) => {
        state.t = Math.max(0, Math.min(t, tEnd()));
        draw();
      },
      setCase: (c) => {
        state.kase = c || state.kase;
        state.t = Math.min(state.t, tEnd());
        draw();
      },
      frameSvg: player.frameSvg,
    };
    speed.addEventListener('change', () => {
      state.speed = Number(speed.value);
    });
    exag.addEventListener('change', () => {
      state.exaggeration = Math.max(1, Number(exag.value) || 1);
      draw();
    });
    scrub.addEventListener('input', () => api.seek((Number(scrub.value) / 1000) * tEnd()));
    exportFrame.addEventListener('click', () =>
      download(`${o.frameName}_t${timeText(frameTime())}.svg`, api.frameSvg(), 'image/svg+xml'),
    );
    return api;
  }

  /** The building of a lumped run: floors, isolator, walls, neighbours and impact flashes. */
  function makeAnimation(parent, firstCase) {
    const { width: W, height: H } = historyViews.building;
    const groundY = H - 40;
    const widthMain = 160;
    /** The building at history sample i. */
    function frame(i, tText) {
      // The case's own model (cases of overlaid runs may differ).
      const { resolved: r, nMain, isolated } = state.kase;
      const storeyH = 300 / (Math.max(nMain, 4) + 0.5);
      // Drawing scale: a storey is 3 m; displacements and gaps are drawn `exaggeration` times larger.
      const pxPerM = storeyH / 3;
      const u = state.kase.history.displacement.values[i];
      const e = state.exaggeration * pxPerM;
      const cx = W / 2;
      const parts = [];
      const line = (x1, y1, x2, y2, color, w) =>
        parts.push(
          `<line x1="${x1.toFixed(1)}" y1="${y1.toFixed(1)}" x2="${x2.toFixed(1)}" y2="${y2.toFixed(1)}" ` +
            `stroke="${color}" stroke-width="${w}"/>`,
        );
      line(0, groundY, W, groundY, '#654', 3);
      // Main building: level 0 is the isolation level (on the isolators) or floor 1.
      const levelY = (k) => groundY - (isolated ? 18 + k * storeyH : (k + 1) * storeyH);
      const xs = u.slice(0, nMain).map((v) => cx + v * e);
      if (isolated) {
        for (const dx of [-widthMain / 2 + 15, widthMain / 2 - 15])
          line(cx + dx, groundY, xs[0] + dx, levelY(0), '#888', 5);
      }
      for (const side of [-1, 1]) {
        let px = cx + (side * widthMain) / 2;
        let py = groundY;
        for (let k = isolated ? 0 : -1; k < nMain; ++k) {
          const x = (k < 0 ? cx : xs[k]) + (side * widthMain) / 2;
          const y = k < 0 ? groundY : levelY(k);
          if (k >= (isolated ? 1 : 0)) line(px, py, x, y, '#345', 3);
          px = x;
          py = y;
        }
      }
      for (let k = 0; k < nMain; ++k)
        line(xs[k] - widthMain / 2, levelY(k), xs[k] + widthMain / 2, levelY(k), '#123', 6);
      // Moat walls at the gap on either side of the isolation level.
      for (const side of ['left', 'right']) {
        const w = r.walls && r.walls[side];
        if (!w || !w.present) continue;
        const s = side === 'right' ? 1 : -1;
        const x = cx + s * (widthMain / 2 + w.gap * e);
        parts.push(
          `<rect x="${(s > 0 ? x : x - 14).toFixed(1)}" y="${(levelY(0) - 16).toFixed(1)}" width="14" ` +
            `height="${(groundY - levelY(0) + 16).toFixed(1)}" fill="#999"/>`,
        );
      }
      // Neighbours: fixed-base shear buildings across their separation.
      let offset = nMain;
      for (const side of ['left', 'right']) {
        const nb = r.neighbours && r.neighbours[side];
        if (!nb || !nb.present) continue;
        const s = side === 'right' ? 1 : -1;
        const face = cx + s * (widthMain / 2 + nb.separation * e);
        const wN = 120;
        const base = face + (s * wN) / 2;
        const nx = u.slice(offset, offset + nb.n_storeys).map((v) => base + v * e);
        const ny = (k) => levelY(k + (isolated ? 1 : 0));
        for (const side2 of [-1, 1]) {
          let px = base + (side2 * wN) / 2;
          let py = groundY;
          for (let k = 0; k < nb.n_storeys; ++k) {
            line(px, py, nx[k] + (side2 * wN) / 2, ny(k), '#575', 3);
            px = nx[k] + (side2 * wN) / 2;
            py = ny(k);
          }
        }
        for (let k = 0; k < nb.n_storeys; ++k) line(nx[k] - wN / 2, ny(k), nx[k] + wN / 2, ny(k), '#353', 6);
        offset += nb.n_storeys;
      }
      // Impacts flash with their force.
      const cf = state.kase.history.contact_force;
      if (cf) {
        const f = Array.isArray(cf.values[i]) ? cf.values[i] : [cf.values[i]];
        state.kase.summary.contacts.forEach((c, k) => {
          if (!(f[k] > 0)) return;
          const m = /^(left|right)_(wall|neighbour_floor(\d+))$/.exec(c.name);
          if (!m) return;
          const s = m[1] === 'right' ? 1 : -1;
          const level = m[2] === 'wall' ? 0 : Number(m[3]) - (isolated ? 0 : 1);
          const x = xs[level] + (s * widthMain) / 2;
          const y = levelY(level);
          const rr = 6 + 24 * Math.sqrt(f[k] / Math.max(c.peak_force, 1));
          parts.push(
            `<circle cx="${x.toFixed(1)}" cy="${y.toFixed(1)}" r="${rr.toFixed(1)}" fill="#e00" ` +
              'fill-opacity="0.6" class="impact"/>',
          );
          // The force beside its circle, outwards (levels are a storey apart: labels never meet),
          // on a white box over the walls and neighbours.
          const text = `${fmt(f[k] * 1e-6, 3)} MN`;
          const w = 7.4 * text.length + 6;
          const x0 = s > 0 ? x + rr + 2 : x - rr - 2 - w;
          parts.push(
            `<rect class="impact-label-box" x="${x0.toFixed(1)}" y="${(y - 9).toFixed(1)}" width="${w.toFixed(1)}" ` +
              'height="18" rx="3" fill="#fff" fill-opacity="0.9" stroke="#b00" stroke-width="0.5"/>',
          );
          parts.push(
            `<text class="impact-label" x="${(x0 + w / 2).toFixed(1)}" y="${(y + 4.5).toFixed(1)}" font-size="13" ` +
              `text-anchor="middle" fill="#b00">${text}</text>`,
          );
        });
      }
      parts.push(
        `<text x="10" y="20" font-size="14">${escapeXml(state.kase.label)}: t = ${tText} s, ` +
          `displacements ×${state.exaggeration}</text>`,
      );
      return parts.join('');
    }

    const api = historyPlayer(parent, 'building', frame);
    const state = api.state;
    api.setCase(firstCase);
    return api;
  }

  Object.assign(kimp, { makePlayer, historyViews, historyPlayer, makeAnimation });
})();
