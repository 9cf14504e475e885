#!/usr/bin/env bash
# Convergence of the engineer's quantities of the inelastic dynamic FEM on a wall mesh that does
# not lock: the reinforced moat wall with its backfill (data/scenes/fem_reinforced_wall.yaml:
# damaged concrete with bars, geostatic medium_dense_sand) at H = 1.25, 1.50 and 2.00 m, 1 m/s,
# `mesh.wall_aspect_max: 1`, `dynamics.end_time: 100 ms`, on the two finest levels of the study's
# fidelity ladder (2.5 and 1.25 cm). One `kimp fem` per level (all three heights), on RANKS MPI
# ranks. Prints the run times, then per height the quantities of both levels, their change
# (the numerical error; target <= 5 %) and the impulse-momentum check of each record (target
# within 2 %). With HOLD (a time in ms) the runs are held that long (the stop rule off:
# separation_hold_time = end_time = HOLD) so that the wall face at the end is the settled
# permanent displacement.
# KIMP_LADDER_HEIGHTS (default "1.25 1.5 2.0", in m) picks the heights.
# Usage: bench/fem_ladder.sh [BUILD_DIR (default: build)] [RANKS (default: 1)] [HOLD_MS]
set -euo pipefail
source "$(dirname "$0")/lib.sh"
bench_init fem_ladder.sh 1 "$@"
ranks="${2:-1}"
hold="${3:-}"
heights="$(printf '"%s m", ' ${KIMP_LADDER_HEIGHTS:-1.25 1.5 2.0})"
bench_require fem time
bench_workdir

echo "kimp fem, reinforced moat wall, wall_aspect_max 1, 2.5 / 1.25 cm, $ranks rank(s)" \
  "($(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
for h in 2.5 1.25; do
  {
    grep -v '^wall_heights:' "$root/data/scenes/fem_reinforced_wall.yaml"
    printf '%s\n' "wall_heights: [${heights%, }]" \
      "mesh: {h_contact: \"$h cm\", wall_aspect_max: 1}" 'slab: {velocity: "1.0 m/s"}' \
      'output: {frame_interval: "0 ms"}'
    if [[ -n "$hold" ]]; then
      printf '%s\n' "dynamics: {end_time: \"$hold ms\", separation_hold_time: \"$hold ms\"}"
    else
      printf '%s\n' 'dynamics: {end_time: "100 ms"}'
    fi
  } > "$work/level_$h.yaml"
  launcher=()
  [[ "$ranks" -gt 1 ]] && launcher=(mpirun -np "$ranks")
  /usr/bin/time -o "$work/time_$h" -f "%e %U %S" "${launcher[@]}" "$kimp" fem "$work/level_$h.yaml" \
    -o "$work/out_$h" -q --accept-cost
  read -r wall user sys_ < <(tail -1 "$work/time_$h")
  echo "level $h cm: process wall $wall s, CPU $(python3 -c "print(f'{$user + $sys_:.1f}')") s" \
    "(load $(cut -d' ' -f1-3 /proc/loadavg))"
done

python3 - "$work/out_2.5/summary.json" "$work/out_1.25/summary.json" <<'PY'
import json, sys
coarse, fine = ({c["name"]: c for c in json.load(open(p))["cases"]} for p in sys.argv[1:3])
rows = [("first peak force (kN/m)", "first_peak_force", 1e-3),
        ("impulse of the first pulse (N s/m)", "first_peak_impulse", 1.0),
        ("energy-equivalent resistance (kN/m)", "energy_equivalent_resistance", 1e-3),
        ("largest slab travel (mm)", "max_slab_displacement", 1e3),
        ("largest wall displacement (mm)", "max_wall_displacement", 1e3),
        ("time to stop the slab (ms)", "time_to_stop", 1e3),
        ("wall face at the end (mm)", "wall_residual_displacement", 1e3),
        ("largest bar strain / eps_y", "max_bar_strain_ratio", 1.0),
        ("its height (m)", "max_bar_strain_height", 1.0),
        ("apparent COR", "apparent_cor", 1.0)]
for name in coarse:
    if name not in fine:
        continue
    a, b = coarse[name], fine[name]
    print(f"\n{name}: 2.5 cm {a['n_dofs']} DoFs, {a['n_steps']} steps, solver {a['wall_time']:.1f} s, "
          f"stopped on {a.get('stopped_on')}; "
          f"1.25 cm {b['n_dofs']} DoFs, {b['n_steps']} steps, solver {b['wall_time']:.1f} s, "
          f"stopped on {b.get('stopped_on')}")
    print(f"  {'quantity':38s} {'2.5 cm':>10s} {'1.25 cm':>10s} {'change':>8s}")
    for label, key, scale in rows:
        if key not in a or key not in b:
            print(f"  {label:38s} {'-':>10s} {'-':>10s}")
            continue
        x, y = a[key] * scale, b[key] * scale
        change = abs(x - y) / max(abs(y), 1e-30) * 100
        verdict = "pass" if change <= 5.0 else "FAIL"
        print(f"  {label:38s} {x:10.4g} {y:10.4g} {change:7.1f} % {verdict}")
    for lvl, c in (("2.5 cm", a), ("1.25 cm", b)):
        r = c.get("impulse_momentum_ratio")
        ok = "ok" if r is not None and abs(r - 1) <= 0.02 else "FAIL"
        print(f"  impulse-momentum {lvl}: {r:.4f} ({ok}); stored share {c.get('stored_energy_share', float('nan')):.3f}")
PY
