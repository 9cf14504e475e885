#!/usr/bin/env bash
# Convergence of the engineer's quantities of the inelastic dynamic FEM on a wall mesh that does
# not lock: the reinforced moat wall with its backfill (data/scenes/fem_reinforced_wall.yaml:
# damaged concrete with bars, geostatic medium_dense_sand) at H = 1.25, 1.50 and 2.00 m, 1 m/s,
# `mesh.wall_aspect_max: 1`, `dynamics.end_time: 100 ms`, on the two finest levels of the study's
# fidelity ladder (2.5 and 1.25 cm), with the far side on rollers and absorbing
# (`boundary.far`). One `kimp fem` per level and far side (all three heights), on RANKS MPI ranks.
# Prints the run times, then per height the quantities of both levels, their change (the
# numerical error; target <= 5 %), the impulse-momentum check of each record (target within 2 %),
# and the spread between the rollered and the absorbing far side at each level.
# With HOLD (a time in ms) the runs are held that long (the stop rule off:
# separation_hold_time = end_time = HOLD) so that the wall face at the end is the settled
# permanent displacement; the table then has the set, the wall's mean over the last 50 ms (what
# docs/validation.md quotes), and says how far it still vibrates and drifts, how far the two finest
# levels' sets differ, also as a share of the largest wall displacement. With three levels
# (KIMP_LADDER_LEVELS="5 2.5 1.25") each quantity also gets its observed order p = log2(d1/d2)
# and the Richardson estimate of the finest level's error, where its changes shrink.
# KIMP_LADDER_HEIGHTS (default "1.25 1.5 2.0", in m) picks the heights; KIMP_LADDER_FAR
# (default "rollers absorbing"; viscous_spring the third choice) the far sides (the first is the
# reference of the convergence table). KIMP_LADDER_OUT (a directory) keeps the runs there and
# reuses a run whose scene is unchanged and whose summary.json exists (delete the directory to
# rerun). KIMP_LADDER_EXTRA
# (YAML lines) is appended to every scene, e.g. 'contact: {penalty_step_ratio: 0.8}' or
# 'contact: {subcycles: 0}'. KIMP_LADDER_LEVELS (default "2.5 1.25", in cm) picks the levels run.
# KIMP_LADDER_WALL_BARS (YAML map entries) replaces the entries of the scene's
# wall_reinforcement, e.g. 'ratio_y: "0.8 %", ratio_x: "0.2 %"' for perfectly bonded bars in
# the crack band without tension stiffening (the scene before its bars' three keys).
# KIMP_LADDER_SLAB (YAML map entries) replaces the entries of the scene's `slab` section (its
# damping), e.g. 'damping_ratio: 0' for the undamped slab (docs/physics.md §4 "Slab damping");
# the bench adds the slab's velocity. The scene before its base joint and slab damping is
# KIMP_LADDER_SLAB='damping_ratio: 0' with KIMP_LADDER_WALL_BARS='ratio_y: "0.8 %", ratio_x:
# "0.2 %", strain_penetration: "0.13 m", crack_spacing: "0.2 m", tension_stiffening: true'.
# Usage: bench/fem_ladder.sh [BUILD_DIR (default: build)] [RANKS (default: 1)] [HOLD_MS]
set -euo pipefail
source "$(dirname "$0")/lib.sh"
bench_init fem_ladder.sh 1 "$@"
ranks="${2:-1}"
hold="${3:-}"
heights="$(printf '"%s m", ' ${KIMP_LADDER_HEIGHTS:-1.25 1.5 2.0})"
read -r -a fars <<< "${KIMP_LADDER_FAR:-rollers absorbing}"
bench_require fem time
# The slab's entries: the scene's (one line, `slab: {...}`), or KIMP_LADDER_SLAB in their place.
slab_entries="${KIMP_LADDER_SLAB-$(sed -nE 's/^slab: \{(.*)\}$/\1/p' "$root/data/scenes/fem_reinforced_wall.yaml")}"
if [[ -n "${KIMP_LADDER_OUT:-}" ]]; then
  work="$KIMP_LADDER_OUT"
  mkdir -p "$work"
else
  bench_workdir
fi

echo "kimp fem, reinforced moat wall, wall_aspect_max 1, levels ${KIMP_LADDER_LEVELS:-2.5 1.25} cm," \
  "far side ${fars[*]}," \
  "$ranks rank(s) ($(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
for far in "${fars[@]}"; do
  for h in ${KIMP_LADDER_LEVELS:-2.5 1.25}; do
    run="${far}_$h"
    {
      grep -v -e '^wall_heights:' -e '^slab:' "$root/data/scenes/fem_reinforced_wall.yaml" |
        if [[ -n "${KIMP_LADDER_WALL_BARS:-}" ]]; then
          sed -E "s/(wall_reinforcement: \{)[^}]*\}/\1${KIMP_LADDER_WALL_BARS}}/"
        else cat; fi
      printf '%s\n' "wall_heights: [${heights%, }]" \
        "mesh: {h_contact: \"$h cm\", wall_aspect_max: 1}" "slab: {velocity: \"1.0 m/s\"${slab_entries:+, $slab_entries}}" \
        'output: {frame_interval: "0 ms"}' "boundary: {far: $far}"
      if [[ -n "$hold" ]]; then
        printf '%s\n' "dynamics: {end_time: \"$hold ms\", separation_hold_time: \"$hold ms\"}"
      else
        printf '%s\n' 'dynamics: {end_time: "100 ms"}'
      fi
      if [[ -n "${KIMP_LADDER_EXTRA:-}" ]]; then printf '%s\n' "$KIMP_LADDER_EXTRA"; fi
    } > "$work/scene_$run.yaml.new"
    if [[ -f "$work/out_$run/summary.json" && -f "$work/scene_$run.yaml" ]] &&
       cmp -s "$work/scene_$run.yaml.new" "$work/scene_$run.yaml"; then
      rm "$work/scene_$run.yaml.new"
      echo "$far, level $h cm: reusing $work/out_$run"
      continue
    fi
    mv "$work/scene_$run.yaml.new" "$work/scene_$run.yaml"
    launcher=()
    [[ "$ranks" -gt 1 ]] && launcher=(mpirun -np "$ranks")
    /usr/bin/time -o "$work/time_$run" -f "%e %U %S" "${launcher[@]}" "$kimp" fem \
      "$work/scene_$run.yaml" -o "$work/out_$run" -q --accept-cost
    read -r wall user sys_ < <(tail -1 "$work/time_$run")
    echo "$far, level $h cm: process wall $wall s," \
      "CPU $(python3 -c "print(f'{$user + $sys_:.1f}')") s (load $(cut -d' ' -f1-3 /proc/loadavg))"
  done
done

python3 - "$work" "${hold:-0}" "${KIMP_LADDER_LEVELS:-2.5 1.25}" "${fars[@]}" <<'PY'
import csv, json, math, os, sys
work, hold, fars = sys.argv[1], float(sys.argv[2]), sys.argv[4:]
levels = tuple(sys.argv[3].split())  # coarse to fine, as run
coarse, fine = (levels[-2], levels[-1]) if len(levels) > 1 else (levels[0], levels[0])
set_window = 0.05  # s: the set of a held run is the wall's mean over its last 50 ms

def load(far, h):
    p = os.path.join(work, f"out_{far}_{h}", "summary.json")
    return {c["name"]: c for c in json.load(open(p))["cases"]} if os.path.exists(p) else {}

def load_sets(far, h):
    """Per case: (mean, least, largest) wall displacement over the last set_window, m."""
    p = os.path.join(work, f"out_{far}_{h}", "fem_histories.csv")
    if hold <= 0 or not os.path.exists(p):
        return {}
    hist = {}
    for r in csv.DictReader(open(p)):
        hist.setdefault(r["case"], []).append((float(r["time_s"]), float(r["wall_displacement_m"])))
    out = {}
    for case, h_ in hist.items():
        t_end = h_[-1][0]
        w = [u for t, u in h_ if t >= t_end - set_window]
        before = [u for t, u in h_ if t_end - 2 * set_window <= t < t_end - set_window]
        drift = sum(w) / len(w) - sum(before) / len(before) if before else math.nan
        out[case] = (sum(w) / len(w), min(w), max(w), drift)
    return out

runs = {(far, h): load(far, h) for far in fars for h in levels}
sets = {(far, h): load_sets(far, h) for far in fars for h in levels}
for key, cases in runs.items():
    for name, c in cases.items():
        if name in sets[key]:
            c["set_mean"], c["set_least"], c["set_largest"], c["set_drift"] = sets[key][name]
rows = [("first peak force (kN/m)", "first_peak_force", 1e-3),
        ("impulse of the first pulse (N s/m)", "first_peak_impulse", 1.0),
        ("energy-equivalent resistance (kN/m)", "energy_equivalent_resistance", 1e-3),
        ("largest slab travel (mm)", "max_slab_displacement", 1e3),
        ("largest wall displacement (mm)", "max_wall_displacement", 1e3),
        ("time to 95 % of the travel (ms)", "time_to_95_travel", 1e3),
        ("slab velocity zero (ms)", "time_to_stop", 1e3),
        ("wall face at the end (mm)", "wall_residual_displacement", 1e3),
        ("set, mean of the last 50 ms (mm)", "set_mean", 1e3),
        ("point bar strain / eps_y (mesh-dep.)", "max_bar_strain_ratio", 1.0),
        ("  its height (m)", "max_bar_strain_height", 1.0),
        ("gauge bar strain / eps_y", "max_bar_gauge_strain_ratio", 1.0),
        ("  its gauge centre (m)", "max_bar_gauge_strain_height", 1.0),
        ("  gauge length (m)", "bar_gauge_length", 1.0),
        ("bars' plastic work, wall (J/m)", "plastic_dissipation_wall", 1.0),
        ("soil's plastic work (J/m)", "plastic_dissipation_soil", 1.0),
        ("apparent COR", "apparent_cor", 1.0),
        ("contact duration (ms)", "contact_duration", 1e3)]

def val(c, key, scale):
    v = c.get(key) if c else None
    if isinstance(v, dict):
        v = v.get("value")
    return None if v is None or not math.isfinite(v) else v * scale

def change(x, y):
    return abs(x - y) / max(abs(y), 1e-30) * 100

def order(xs):
    """Observed order p = log2(d1/d2) of three levels halving h, and the Richardson estimate of
    the finest level's own error (%), where the changes shrink monotonically."""
    d1, d2 = xs[1] - xs[0], xs[2] - xs[1]
    if d1 == 0 and d2 == 0:
        return "unchanged"
    if d2 == 0 or d1 / d2 <= 1:
        return "not monotone"
    r = d1 / d2
    limit = xs[2] + d2 / (r - 1)
    return f"p {math.log2(r):.2f}, error of {levels[-1]} cm {(xs[2] - limit) / abs(limit) * 100:+.1f} %"

ref = fars[0]
names = list(runs[(ref, fine)] or runs[(ref, coarse)])
for name in names:
    a, b = runs[(ref, coarse)].get(name), runs[(ref, fine)].get(name)
    print(f"\n{name}, far side {ref}:")
    for lvl in levels:
        c = runs[(ref, lvl)].get(name)
        if c:
            print(f"  {lvl} cm: {c['n_dofs']} DoFs, {c['n_steps']} steps "
                  f"({c.get('contact_subcycles', '?')} contact sub-steps each), "
                  f"solver {c['wall_time']:.1f} s, "
                  f"stopped on {c.get('stopped_on')}, stored share "
                  f"{c.get('stored_energy_share', float('nan')):.3f}, impulse-momentum "
                  f"{c.get('impulse_momentum_ratio', float('nan')):.4f} "
                  f"({'ok' if abs(c.get('impulse_momentum_ratio', 0) - 1) <= 0.02 else 'FAIL'})")
    print(f"  {'quantity':38s} " + " ".join(f"{lvl + ' cm':>10s}" for lvl in levels) +
          f" {'change':>8s}" + ("   observed order (three levels)" if len(levels) == 3 else ""))
    for label, key, scale in rows:
        xs = [val(runs[(ref, lvl)].get(name), key, scale) for lvl in levels]
        cells = " ".join("-".rjust(10) if x is None else f"{x:10.4g}" for x in xs)
        x, y = xs[-2] if len(xs) > 1 else None, xs[-1]
        if x is None or y is None:
            print(f"  {label:38s} {cells}")
            continue
        ch = change(x, y)
        tail = f" {ch:7.1f} % {'pass' if ch <= 5.0 else 'FAIL'}"
        if len(xs) == 3 and None not in xs and not label.startswith(" ") and "mesh-dep" not in label:
            tail += f"   {order(xs)}"
        print(f"  {label:38s} {cells}{tail}")
    if b and "set_mean" in b:
        move = val(b, "max_wall_displacement", 1e3)
        diff = abs(a["set_mean"] - b["set_mean"]) * 1e3 if a and "set_mean" in a else float("nan")
        print(f"  set on {fine} cm vibrates over the last 50 ms between {b['set_least'] * 1e3:.3f} "
              f"and {b['set_largest'] * 1e3:.3f} mm and drifts by {b['set_drift'] * 1e3:+.3f} mm "
              f"(mean of the last 50 ms less that of the 50 ms before; a drift beside the "
              f"difference below means the wall has not settled); the two finest levels differ "
              f"by {diff:.3f} mm, {diff / move * 100:.2f} % of the largest wall displacement")
    for far in fars[1:]:
        print(f"  far side {far}: its own change from {coarse} to {fine} cm:")
        for label, key, scale in rows:
            x, y = (val(runs[(far, h)].get(name), key, scale) for h in (coarse, fine))
            if x is not None and y is not None:
                print(f"  {label:38s} {x:10.4g} {y:10.4g} {change(x, y):7.1f} %")
        print(f"  far side {ref} against {far} (spread = |{ref} - {far}| / {far}):")
        print(f"  {'quantity':38s} {'level':>7s} {ref:>10s} {far:>10s} {'spread':>8s}")
        for label, key, scale in rows:
            for h in levels:
                x, y = (val(runs[(f, h)].get(name), key, scale) for f in (ref, far))
                if x is None or y is None:
                    continue
                print(f"  {label:38s} {h + ' cm':>7s} {x:10.4g} {y:10.4g} {change(x, y):7.1f} %")

# The slab's creep to rest, from the histories (the slab's travel integrates its velocity from
# the first contact): where it falls under 0.1 m/s, as a share of its largest travel, and its
# speed when it reaches 95 % of the travel (time_to_95_travel).
from collections import defaultdict
print("\ncreep to rest (slab under 0.1 m/s from ... of its travel; its speed at 95 % of it):")
for far in fars:
    for h in levels:
        path = os.path.join(work, f"out_{far}_{h}", "fem_histories.csv")
        if not os.path.exists(path):
            continue
        cases = defaultdict(list)
        for r in csv.DictReader(open(path)):
            cases[r["case"]].append((float(r["time_s"]), float(r["smoothed_contact_force_N_per_m"]),
                                     float(r["slab_velocity_m_per_s"])))
        for case, hist in cases.items():
            touch = next((i for i, (_, f, _) in enumerate(hist) if f > 0), None)
            if touch is None:
                continue
            x = [0.0]
            for i in range(touch + 1, len(hist)):
                x.append(x[-1] + 0.5 * (hist[i][2] + hist[i - 1][2]) * (hist[i][0] - hist[i - 1][0]))
            v = [hv for _, _, hv in hist[touch:]]
            top = max(x)
            slow = next((i for i in range(len(v)) if v[i] <= 0.1), None)
            at95 = next(i for i in range(len(x)) if x[i] >= 0.95 * top)
            print(f"  {far:10s} {h:>4s} cm {case}: under 0.1 m/s from "
                  f"{'-' if slow is None else f'{100 * x[slow] / top:.1f} %'}, "
                  f"{v[at95]:.3f} m/s at 95 %")
PY
