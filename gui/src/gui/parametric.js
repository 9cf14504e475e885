// kimp gui: the parametric dialog: a sweep over scene keys (lists or ranges) built from the schema,
// run by kimp sweep on the lumped scene being edited.
'use strict';

(function () {
  const { state, getJson, toYaml, fromYaml, sceneYaml, startRun, completeSceneYaml } = kimpGui;
  const el = kimp.el;

  // ---- parametric dialog -------------------------------------------------------------------
  /** Scene keys a sweep can vary: quantities, integers and choices (impact.law). */
  function sweepableKeys(keys, out) {
    for (const k of keys) {
      if (k.keys) sweepableKeys(k.keys, out);
      else if (
        ['quantity', 'optional quantity', 'integer', 'choice', 'flag'].includes(k.type) &&
        !k.path.includes('[]')
      )
        out.push(k);
    }
    return out;
  }

  /**
   * The k that goes with an impact law in a sweep over laws (thesis Table 4.3): n = 1 laws in
   * kN/mm, n = 1.5 laws in kN/mm^1.5; bumper takes its own bumper.k_b (no k).
   */
  const LAW_K = {
    linear: '2500 kN/mm',
    kelvin_voigt: '2500 kN/mm',
    modified_kelvin_voigt: '2500 kN/mm',
    jankowski: '750 kN/mm^1.5',
    hertzdamp: '750 kN/mm^1.5',
    hysteretic: '750 kN/mm^1.5',
  };

  /** The sweep file of the dialog's rows; regenerated on every change, so a run never uses a stale one. */
  function makeSweep() {
    const rows = document.getElementById('param-rows');
    const lines = ['# parameter study made by kimp gui', 'scene: scene.yaml', 'combine: product'];
    const params = [];
    let gap = null;
    for (const row of rows.querySelectorAll('.param-row')) {
      const key = row.querySelector('.param-key').value;
      let keyText = key;
      if (key === 'walls.left.gap' && document.getElementById('param-both').checked)
        keyText = 'walls.left.gap, walls.right.gap';
      if (key.endsWith('.gap') && !gap) gap = key;
      if (row.querySelector('.param-mode').value === 'range') {
        const [f, t, s] = ['from', 'to', 'step'].map((n) => row.querySelector('.param-' + n).value.trim());
        params.push(`  ${keyText}: {from: ${JSON.stringify(f)}, to: ${JSON.stringify(t)}, step: ${JSON.stringify(s)}}`);
      } else {
        const picked = Array.from(row.querySelectorAll('.param-option:checked')).map((b) => b.value);
        const typed = row
          .querySelector('.param-values')
          .value.split(',')
          .map((v) => v.trim())
          .filter((v) => v);
        const values = picked.length ? picked : typed;
        const kOf = (law) => {
          const box = row.querySelector(`.param-k[data-law="${law}"]`);
          return box ? box.value.trim() || box.placeholder : '';
        };
        if (key.endsWith('.law') && picked.some(kOf)) {
          // Each law with its k, set together (a list of maps, labelled by the law).
          const kKey = key.replace(/law$/, 'k');
          const items = picked.map((law) =>
            kOf(law)
              ? `{${key}: ${law}, ${kKey}: ${JSON.stringify(kOf(law))}, label: ${law}}`
              : `{${key}: ${law}, label: ${law}}`,
          );
          params.push(`  ${keyText}: [${items.join(', ')}]`);
        } else params.push(`  ${keyText}: [${values.map((v) => JSON.stringify(v)).join(', ')}]`);
      }
    }
    if (gap) lines.push('report:', '  kind: gap_study', `  gap: ${gap}`, '  title: "Gap sweep (kimp gui)"');
    lines.push('parameters:', ...params);
    document.getElementById('sweep-yaml').value = lines.join('\n') + '\n';
  }

  function addParamRow(path, mode, values) {
    const rows = document.getElementById('param-rows');
    const keys = sweepableKeys(state.schemas.lumped ? state.schemas.lumped.keys : [], []);
    const sel = el(
      'select',
      { class: 'param-key' },
      keys.map((k) =>
        el('option', {
          value: k.path,
          text: `${k.path}${k.unit ? ' [' + k.unit + ']' : ''}${k.type === 'choice' ? ' (choice)' : ''}`,
        }),
      ),
    );
    if (path) sel.value = path;
    const modeSel = el('select', { class: 'param-mode' }, [
      el('option', { value: 'range', text: 'from / to / step' }),
      el('option', { value: 'values', text: 'list of values' }),
    ]);
    const range = ['from', 'to', 'step'].map((n) => el('input', { type: 'text', class: 'param-' + n, placeholder: n }));
    const list = el('input', {
      type: 'text',
      class: 'param-values',
      placeholder: 'values, comma separated ("0.5, 0.7, 0.9")',
    });
    const options = el('span', { class: 'param-options' });
    const row = el('div', { class: 'controls param-row' }, [
      sel,
      modeSel,
      ...range,
      list,
      options,
      el('button', {
        text: '×',
        title: 'remove this parameter',
        onclick: () => {
          row.remove();
          makeSweep();
        },
      }),
    ]);
    const layout = () => {
      const k = keys.find((x) => x.path === sel.value) || {};
      const choice = k.type === 'choice' || k.type === 'flag';
      if (choice) modeSel.value = 'values';
      modeSel.disabled = choice;
      const isRange = modeSel.value === 'range';
      for (const input of range) input.style.display = isRange ? '' : 'none';
      list.style.display = !isRange && !choice ? '' : 'none';
      options.innerHTML = '';
      if (choice) {
        const opts = k.type === 'flag' ? ['false', 'true'] : k.options;
        for (const o of opts) {
          const kBox =
            k.path.endsWith('.law') && LAW_K[o]
              ? el('input', { type: 'text', class: 'param-k', 'data-law': o, placeholder: LAW_K[o], size: 12 })
              : null;
          options.appendChild(
            el('label', { title: kBox ? `${o} with its k (impact.k)` : o }, [
              el('input', { type: 'checkbox', class: 'param-option', value: o }),
              document.createTextNode(' ' + o + ' '),
              kBox,
            ]),
          );
        }
      }
    };
    sel.addEventListener('change', () => {
      layout();
      makeSweep();
    });
    modeSel.addEventListener('change', () => {
      layout();
      makeSweep();
    });
    row.addEventListener('input', makeSweep);
    row.addEventListener('change', makeSweep);
    if (mode) modeSel.value = mode;
    layout();
    if (mode === 'range' && values)
      range.forEach((input, i) => {
        input.value = values[i];
      });
    else if (values) {
      for (const b of options.querySelectorAll('.param-option')) b.checked = values.includes(b.value);
      list.value = values.join(', ');
    }
    rows.appendChild(row);
    makeSweep();
  }

  /** The lumped scene a dialog sweep runs on: the Scene tab's (or the last edited lumped one). */
  function lumpedSceneForSweep() {
    const yaml = state.command === 'lumped' ? sceneYaml() : state.saved.lumped ? state.saved.lumped.yaml : '';
    const scene = yaml.trim() ? fromYaml(yaml) : {};
    if (document.getElementById('param-companion').checked) {
      scene.integration = scene.integration || {};
      scene.integration.companion = true;
    }
    return toYaml(scene, 0) + '\n';
  }

  async function initParametric() {
    state.schemas.lumped = state.command === 'lumped' ? state.schema : await getJson('/api/schema/lumped');
    document.getElementById('param-add').addEventListener('click', () => addParamRow());
    document.getElementById('param-make').addEventListener('click', makeSweep);
    document.getElementById('param-both').addEventListener('change', makeSweep);
    document.getElementById('param-run').addEventListener('click', async () => {
      const text = document.getElementById('sweep-yaml').value;
      // Progress, log and errors on this tab (prefix "param").
      startRun(
        'sweep',
        await completeSceneYaml('lumped', lumpedSceneForSweep()),
        text.trim() ? text : (makeSweep(), document.getElementById('sweep-yaml').value),
        {
          prefix: 'param',
          name: document.getElementById('run-name').value.trim(),
          notes: document.getElementById('run-notes').value.trim(),
        },
      );
    });
    addParamRow('walls.left.gap', 'range', ['10 cm', '20 cm', '5 cm']);
  }

  Object.assign(kimpGui, { initParametric });
})();
