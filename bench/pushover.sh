#!/usr/bin/env bash
# Whole-process timing of `kimp fem --pushover` per wall height: the reinforced 0.25 m wall
# (damage_plasticity, 0.5 % vertical bars) with a Mohr-Coulomb sand backfill, geostatic state and
# contact interface, pushed to 5 % of its height, on the coarse (5 cm) and the medium (2.5 cm)
# mesh; and the cyclic push (unload at 1 cm) on the coarse mesh. Prints wall and CPU time per run
# and per height.
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
scene() { # $1: h_contact, $2: unload_at list
  cat <<YAML
wall_heights: ["1.25 m"]
mesh: {h_contact: "$1", h_max: "20 cm", grading: 1.2}
geometry: {backfill_width: "6 m"}
interface: {model: contact}
materials:
  concrete:
    model: damage_plasticity
    f_cm: "38 MPa"
    wall_reinforcement: {ratio_y: "0.5 %", hardening: 0.01}
  soil: {model: mohr_coulomb, phi: 30, c: "1 kPa", psi: 0, tension_cutoff: "1 kPa"}
pushover: {increment: "1 mm", unload_at: $2}
YAML
}
scene "5 cm" "[]" > "$work/coarse.yaml"
scene "2.5 cm" "[]" > "$work/medium.yaml"
scene "5 cm" '["10 mm"]' > "$work/cyclic.yaml"
for name in coarse medium cyclic; do
  for ((i = 1; i <= runs; ++i)); do
    rm -rf "$work/out"
    /usr/bin/time -f "$name run $i: %e s wall, %U s user, %M kB" \
      "$kimp" fem "$work/$name.yaml" --pushover -o "$work/out" > /dev/null 2>"$work/err" || { cat "$work/err" >&2; exit 1; }
    tail -1 "$work/err"
    grep -h "^H" "$work/out/pushover_summary.csv" | awk -F, '{printf "  %s: capacity %.4g kN/m, k0 %.4g kN/mm/m, %s cells, %.3g s\n", $1, $3/1e3, $5/1e6, $11, $14}'
  done
done
