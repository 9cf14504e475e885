#!/usr/bin/env bash
# Whole-process timing of `kimp lumped` on the 48 s Kobe KJMA run of thesis Table 4.3 (4-storey
# isolated building, walls at 15 cm, Δt = 2e-5 s, histories every 0.01 s): impact springs
# (modified Kelvin-Voigt, 2500 kN/mm, rigid walls; 5 DoFs) against yielding walls (the element
# an inelastic study derives at H = 1.25 m for the default site with bars: a linear contact
# spring of 1191 kN/mm/m, cracked wall 43.09 kN/mm/m capped at 125.4 kN/m, dashpot
# 394.5 kN*s/m^2, wall DOF 20.8 t; 7 DoFs). Prints the case's solver time per run and per
# DoF-step (docs/performance.md "Yielding walls").
# Usage: bench/yielding_wall.sh [BUILD_DIR (default: build)] [RUNS (default: 3)]
# The record is read in place: --records-dir from KIMP_RECORDS_DIR, else ../shared/data/records
# beside the source tree.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
bench_init yielding_wall.sh 3 "$@"
bench_require records RSN1106_KOBE_KJM000.AT2
bench_workdir
common='building: {kind: isolated, n_storeys: 4}
ground_motion: {record: RSN1106_KOBE_KJM000, duration: "48 s"}
integration: {method: cdm, dt: "2e-5 s", output_interval: "0.01 s"}'
cat > "$work/springs.yaml" <<YAML
$common
walls:
  left: {gap: "15 cm", mass: "500 t"}
  right: {gap: "15 cm", mass: "500 t"}
impact: {law: modified_kelvin_voigt, k: "2500 kN/mm", cor: 0.7}
YAML
wall='{gap: "15 cm", mass: "500 t", sdof_mass: "20.8 t", yielding: {height: "1.25 m", stiffness: "43.09 kN/mm/m", capacity: "125.4 kN/m", radiation_damping: "394.5 kN*s/m^2"}}'
cat > "$work/yielding.yaml" <<YAML
$common
walls:
  left: $wall
  right: $wall
impact: {law: linear, k: "33090 kN/mm"}
YAML

# measure NAME: RUNS runs of `kimp lumped`; one line per run (solver time from summary.json).
measure() {
  local name="$1"
  for ((i = 0; i < runs; ++i)); do
    rm -rf "$work/out"
    "$kimp" lumped "$work/$name.yaml" -o "$work/out" --records-dir "$records" > "$work/log" 2>&1 \
      || { cat "$work/log" >&2; exit 1; }
    python3 - "$work/out/summary.json" "$name" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["cases"][0]
dofs = len(c["peaks"]["displacement"])
n = c["n_steps"]
walls = c.get("walls", [])
extra = "".join(f", {w['name']} residual {100 * w['residual_displacement']:.3g} cm" for w in walls)
per = f"{1e9 * c['wall_time'] / (n * dofs):.1f} ns per DoF-step ({dofs} DoFs)"
print(f"{sys.argv[2]:9s} {c['wall_time']:.3f} s, {n} steps, {per}, {c['n_impacts']} impacts{extra}")
PY
  done
}
measure springs
measure yielding
