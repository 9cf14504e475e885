#!/usr/bin/env bash
# Whole-process timing of `kimp fem` with inelastic materials (Mohr-Coulomb backfill, damaged
# concrete): data/scenes/fem_inelastic.yaml (the default scene at H = 1.25 m, 2.5 cm contact
# elements, 1 m/s) on 1 and 2 MPI ranks, and the same materials on the quick scene (rigid slab,
# 5 cm), and the reinforced moat wall (geostatic sand, bars) at 5 cm. Prints wall and CPU time per
# run and the solver's steps and time per step. With LADDER as third argument: only the reinforced
# moat wall at H = 1.25 and 2.0 m on each level of the study's fidelity ladder (5 / 2.5 / 1.25 cm),
# one rank, with the engineer's quantities of each run.
# Usage: bench/fem_inelastic.sh [BUILD_DIR (default: build)] [RUNS (default: 3)] [ladder]
set -euo pipefail
source "$(dirname "$0")/lib.sh"
bench_init fem_inelastic.sh 3 "$@"
mode="${3:-}"
bench_require fem time
bench_workdir
cat > "$work/quick.yaml" <<'YAML'
# data/scenes/fem_quick.yaml (rigid slab, 5 cm) with the materials of fem_inelastic.yaml.
wall_heights: ["1.25 m"]
mesh: {h_contact: "5 cm", h_max: "25 cm", grading: 1.5}
slab: {rigid: true, velocity: "1.0 m/s"}
dynamics: {end_time: "40 ms", output_interval: "0.02 ms"}
materials:
  concrete: {model: damage_plasticity, f_cm: "38 MPa"}
  soil: {model: mohr_coulomb, preset: medium_dense_sand, c: "5 kPa"}
YAML
# The reinforced moat wall of docs/validation.md (data/scenes/fem_reinforced_wall.yaml: geostatic
# cohesionless backfill, bars in wall and slab) at 5 cm: the wall yields, the contact lasts 35 ms,
# the backfill stays plastic (docs/performance.md's timings of it are of perfect bond, before the
# scene carried its bars' strain penetration, crack spacing, tension stiffening, base joint and
# slab damping). The scene's one-line `slab: {...}` gets the slab's velocity.
{ sed -E 's/^slab: \{/slab: {velocity: "1.0 m\/s", /' "$root/data/scenes/fem_reinforced_wall.yaml"
  printf '%s\n' 'mesh: {h_contact: "5 cm"}'
  grep -q '^slab:' "$root/data/scenes/fem_reinforced_wall.yaml" ||
    printf '%s\n' 'slab: {velocity: "1.0 m/s"}'; } > "$work/moat_wall.yaml"

# measure NAME RANKS SCENE: RUNS runs of `kimp fem`; one line per run.
measure() {
  local name="$1" ranks="$2" scene="$3"
  for ((i = 0; i < runs; ++i)); do
    rm -rf "$work/out"
    local launcher=()
    [[ "$ranks" -gt 1 ]] && launcher=(mpirun -np "$ranks")
    /usr/bin/time -o "$work/time" -f "%e %U %S" "${launcher[@]}" "$kimp" fem "$scene" -o "$work/out" -q
    python3 - "$name" "$work/time" "$work/out/summary.json" <<'PY'
import json, sys
name, time_file, summary = sys.argv[1:4]
wall, user, sys_ = (float(x) for x in open(time_file).read().split()[-3:])
c = json.load(open(summary))["cases"][0]
steps = c["n_steps"]
print(f"{name:34s} wall {wall:6.2f} s  cpu {user + sys_:6.2f} s  solver {c['wall_time']:6.2f} s  "
      f"{int(steps)} steps  {1e6 * c['wall_time'] / steps:7.1f} us/step  "
      f"peak {c['peak_force'] / 1e3:.6g} kN/m  COR {c['apparent_cor']:.6g}")
q = lambda key, scale=1.0: f"{c[key] * scale:.4g}" if key in c else "-"
print(f"{'':34s} first peak {q('first_peak_force', 1e-3)} kN/m, impulse {q('first_peak_impulse')} "
      f"N s/m, R_e {q('energy_equivalent_resistance', 1e-3)} kN/m, slab {q('max_slab_displacement', 1e3)} "
      f"mm, wall {q('max_wall_displacement', 1e3)} mm, stop {q('time_to_95_travel', 1e3)} ms "
      f"(velocity zero {q('time_to_stop', 1e3)} ms), end "
      f"{q('wall_residual_displacement', 1e3)} mm, bars {q('max_bar_strain_ratio')} at "
      f"{q('max_bar_strain_height')} m (point), {q('max_bar_gauge_strain_ratio')} at "
      f"{q('max_bar_gauge_strain_height')} m (gauge), I/mv {q('impulse_momentum_ratio')}, "
      f"{c.get('stopped_on', '')}")
PY
  done
}

if [[ "$mode" == ladder ]]; then
  echo "kimp fem, reinforced moat wall on the fidelity ladder, $runs runs each ($(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
  for height in 1.25 2.0; do
    for h in 5 2.5 1.25; do
      sed -e "s/\"1.25 m\"/\"$height m\"/" -e "s/h_contact: \"5 cm\"/h_contact: \"$h cm\"/" \
        "$work/moat_wall.yaml" > "$work/level.yaml"
      measure "moat wall, H $height m, $h cm, 1 rank" 1 "$work/level.yaml"
    done
  done
  exit 0
fi
echo "kimp fem, inelastic materials, $runs runs each ($(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
measure "quick scene (rigid slab, 5 cm), 1 rank" 1 "$work/quick.yaml"
measure "fem_inelastic.yaml, 1 rank" 1 "$root/data/scenes/fem_inelastic.yaml"
measure "fem_inelastic.yaml, 2 ranks" 2 "$root/data/scenes/fem_inelastic.yaml"
measure "reinforced moat wall, 5 cm, 1 rank" 1 "$work/moat_wall.yaml"
