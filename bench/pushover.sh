#!/usr/bin/env bash
# Whole-process timing of `kimp fem --pushover` per wall height (1.25 m, pushed to 5 % of it):
# the bare reinforced 0.25 m wall (damage_plasticity, 0.5 % vertical bars, tensile strength cut
# to 10 %: with the full one the push stalls at the first cracks) and the elastic wall
# against Mohr-Coulomb sand (geostatic state, contact interface), each on the coarse (5 cm) and
# medium (2.5 cm) mesh; the sand case cyclic (unload at 1 cm); and the reinforced wall with sand
# (reported as failed while its Newton stalls). Prints wall and CPU time per run and per height.
# Usage: bench/pushover.sh [BUILD_DIR (default: build)] [RUNS (default: 1)]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
runs="${2:-1}"
kimp="$build/kimp"
[[ -x "$kimp" && -x "$build/kimp-fem" ]] || { echo "pushover.sh: build the target kimp (with FEM) in $build" >&2; exit 1; }
[[ -x /usr/bin/time ]] || { echo "pushover.sh: needs /usr/bin/time (Debian package time)" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export KIMP_DATA_DIR="$root"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
scene() { # $1: h_contact, $2: unload_at list, $3: concrete model, $4: with_backfill
  local concrete="{model: damage_plasticity, f_cm: \"38 MPa\", f_ctm: \"0.29 MPa\", wall_reinforcement: {ratio_y: \"0.5 %\", hardening: 0.01}}"
  [[ "$3" == elastic ]] && concrete="{model: elastic}"
  local interface=contact
  [[ "$4" == false ]] && interface=bonded
  cat <<YAML
wall_heights: ["1.25 m"]
mesh: {h_contact: "$1", h_max: "20 cm", grading: 1.2}
geometry: {backfill_width: "6 m", with_backfill: $4}
interface: {model: $interface}
materials:
  concrete: $concrete
  soil: {model: mohr_coulomb, phi: 30, c: "1 kPa", psi: 0, tension_cutoff: "1 kPa"}
pushover: {increment: "1 mm", unload_at: $2}
YAML
}
scene "5 cm" "[]" damage_plasticity false > "$work/bare_coarse.yaml"
scene "2.5 cm" "[]" damage_plasticity false > "$work/bare_medium.yaml"
scene "5 cm" "[]" elastic true > "$work/sand_coarse.yaml"
scene "2.5 cm" "[]" elastic true > "$work/sand_medium.yaml"
scene "5 cm" '["10 mm"]' elastic true > "$work/sand_cyclic.yaml"
scene "5 cm" "[]" damage_plasticity true > "$work/reinforced_sand.yaml"
for name in bare_coarse bare_medium sand_coarse sand_medium sand_cyclic reinforced_sand; do
  for ((i = 1; i <= runs; ++i)); do
    rm -rf "$work/out"
    if /usr/bin/time -f "$name run $i: %e s wall, %U s user, %M kB" \
      "$kimp" fem "$work/$name.yaml" --pushover -o "$work/out" > /dev/null 2>"$work/err"; then
      tail -1 "$work/err"
      grep -h "^H" "$work/out/pushover_summary.csv" | awk -F, '{printf "  %s: capacity %.4g kN/m, k0 %.4g kN/mm/m, %s cells, %.3g s\n", $1, $3/1e3, $5/1e6, $11, $14}'
    else
      echo "$name run $i: failed: $(grep -m1 error "$work/err" | cut -c1-160)"
    fi
  done
done
