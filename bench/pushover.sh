#!/usr/bin/env bash
# Whole-process timing of `kimp fem --pushover`, one process per case and wall height, pushed to
# 5 % of the height: the reinforced 0.25 m wall (damage_plasticity with MC2010's full tensile
# strength, 0.5 % vertical bars with 1 % hardening, IMPL-EX damage update) against Mohr-Coulomb
# sand (phi 30, c 1 kPa, psi 0; geostatic state; contact interface) at H = 1.25, 1.50 and
# 2.00 m on the 10 cm, 5 cm and 2.5 cm meshes (the capacity's convergence between the two
# finest levels; rotating crack frame and IMPL-EX step control, the pushover's defaults); at
# H = 1.25 m, 5 cm, the same with 0.25 mm steps (the IMPL-EX step error); the bare wall with
# MC2010's full tensile strength; the elastic wall against the sand, monotonic and cyclic
# (unload at 1 cm). Prints capacity, steps and CPU (user) time per run, then per height the change
# of the capacity and of the force at 1 cm from each level to the next finer one.
# Usage: bench/pushover.sh [BUILD_DIR (default: build)] [RUNS (default: 1)]
# KIMP_PUSHOVER_LEVELS (default "10cm 5cm 2.5cm") and KIMP_PUSHOVER_HEIGHTS (default "1.25 1.50
# 2.00") choose the convergence study (the 2.5 cm level takes 1-6 minutes of CPU per height; the
# 1.25 cm level 9-17 minutes or more; with the automatic step control the 1.25 cm level runs to 5 %
# drift in 1 mm steps, docs/validation.md "The study's two finest levels"; the study's two
# finest levels: KIMP_PUSHOVER_LEVELS="2.5cm 1.25cm"). KIMP_PUSHOVER_INCREMENT (default "1 mm")
# is the largest step of the convergence study. Each run prints its steps, Newton iterations,
# steps halved for Newton and the smallest step.
# KIMP_PUSHOVER_EXTRAS=0 skips the cases after the convergence study. KIMP_PUSHOVER_UNLOAD_DRIFTS
# (e.g. "1 2"; default none) unloads the convergence study's pushes to zero force and reloads at
# those drifts (% of H), the study's element's unloadings; each unloading's secant is printed.
# KIMP_PUSHOVER_WALL_BARS (YAML map entries) is added to the wall's bars, e.g. 'crack_spacing:
# "0.2 m", tension_stiffening: true'.
# KIMP_PUSHOVER_KEEP=DIR keeps each run's output directory and log in DIR/<case> (with
# KIMP_PUSHOVER_VERBOSE=1, the default when keeping, the log has the static solver's line per
# step and per halved step).
set -euo pipefail
source "$(dirname "$0")/lib.sh"
bench_init pushover.sh 1 "$@"
levels="${KIMP_PUSHOVER_LEVELS:-10cm 5cm 2.5cm}"
heights="${KIMP_PUSHOVER_HEIGHTS:-1.25 1.50 2.00}"
extras="${KIMP_PUSHOVER_EXTRAS:-1}"
increment="${KIMP_PUSHOVER_INCREMENT:-1 mm}"
unload_drifts="${KIMP_PUSHOVER_UNLOAD_DRIFTS:-}"
keep="${KIMP_PUSHOVER_KEEP:-}"
verbose=()
[[ "${KIMP_PUSHOVER_VERBOSE:-${keep:+1}}" == 1 ]] && verbose=(-v)
bench_require fem time
export KIMP_DATA_DIR="$root"
bench_workdir
scene() { # $1: h_contact, $2: unload_at list, $3: concrete model, $4: with_backfill, $5: height, $6: increment
  local concrete="{model: damage_plasticity, f_cm: \"38 MPa\", wall_reinforcement: {ratio_y: \"0.5 %\", hardening: 0.01${KIMP_PUSHOVER_WALL_BARS:+, $KIMP_PUSHOVER_WALL_BARS}}}"
  [[ "$3" == elastic ]] && concrete="{model: elastic}"
  local interface=contact
  [[ "$4" == false ]] && interface=bonded
  cat <<YAML
wall_heights: ["$5 m"]
mesh: {h_contact: "$1", h_max: "20 cm", grading: 1.2}
geometry: {backfill_width: "6 m", with_backfill: $4}
interface: {model: $interface}
materials:
  concrete: $concrete
  soil: {model: mohr_coulomb, phi: 30, c: "1 kPa", psi: 0, tension_cutoff: "1 kPa"}
pushover: {increment: "$6", unload_at: $2}
YAML
}
cases=()
for height in $heights; do
  for level in $levels; do
    name="reinforced_sand_H${height}_${level}"
    unload="[$(for d in $unload_drifts; do awk -v h="$height" -v d="$d" 'BEGIN { printf "\"%.6g mm\", ", h * d * 10 }'; done | sed 's/, $//')]"
    scene "${level%cm} cm" "$unload" damage_plasticity true "$height" "$increment" > "$work/$name.yaml"
    cases+=("$name")
  done
done
if [[ "$extras" != 0 ]]; then
  scene "5 cm" "[]" damage_plasticity true 1.25 "0.25 mm" > "$work/reinforced_sand_H1.25_5cm_step0.25mm.yaml"
  scene "5 cm" "[]" damage_plasticity false 1.25 "1 mm" > "$work/bare_full_ft.yaml"
  scene "5 cm" "[]" elastic true 1.25 "1 mm" > "$work/elastic_sand.yaml"
  scene "5 cm" '["10 mm"]' elastic true 1.25 "1 mm" > "$work/elastic_sand_cyclic.yaml"
  cases+=(reinforced_sand_H1.25_5cm_step0.25mm bare_full_ft elastic_sand elastic_sand_cyclic)
fi
declare -A capacity force_1cm # of each case's last run, N/m
for name in "${cases[@]}"; do
  for ((i = 1; i <= runs; ++i)); do
    rm -rf "$work/out"
    if /usr/bin/time -f "$name run $i: %e s wall, %U s user, %M kB" \
      "$kimp" fem "$work/$name.yaml" --pushover "${verbose[@]}" -o "$work/out" > /dev/null 2>"$work/err"; then
      tail -1 "$work/err"
      grep -ho "[0-9]* steps, [0-9]* Newton iterations, [0-9]* steps halved for Newton (smallest step [^)]*)" "$work/err" | sed 's/^/  /' || true
      # Each unloading: from its first point's predecessor to zero force (the secant).
      awk -F, '/^H/ { u = $3 * 1e3; f = $4 * 1e-3
          if ($6 == 1 && !un) { un = 1; u0 = pu; f0 = pf }
          if ($6 == 1 && un && f <= 0 && pf > 0) { set = pu + (u - pu) * pf / (pf - f)
            printf "  unloading from %.4g mm (%.4g kN/m): set %.4g mm, secant %.4g kN/mm/m\n", u0, f0, set, f0 / (u0 - set) }
          if ($6 == 0) un = 0
          pu = u; pf = f }' "$work/out/pushover.csv"
      grep -h "^H" "$work/out/pushover_summary.csv" | awk -F, 'function g(x, s) { return x ~ /nan/ ? "-" : sprintf("%.4g", x * s) }
        {printf "  %s: capacity %s kN/m at %s mm, k0 %s, cracked %s, K_ur %s kN/mm/m, set %s mm, %s cells\n", $1, g($3, 1e-3), g($4, 1e3), g($5, 1e-6), g($6, 1e-6), g($8, 1e-6), g($9, 1e3), $11}'
      echo "  steps: $(($(grep -c "^H" "$work/out/pushover.csv") - 1))"
      [[ -n "$keep" ]] && mkdir -p "$keep" && rm -rf "${keep:?}/$name" && cp -r "$work/out" "$keep/$name" && cp "$work/err" "$keep/$name/log"
      capacity[$name]="$(grep -h "^H" "$work/out/pushover_summary.csv" | cut -d, -f3)"
      force_1cm[$name]="$(grep -h "^H" "$work/out/pushover_summary.csv" | cut -d, -f7)"
    else
      echo "$name run $i: failed: $(grep -m1 error "$work/err" | cut -c1-160)"
      [[ -n "$keep" ]] && mkdir -p "$keep/$name" && cp "$work/err" "$keep/$name/log"
    fi
  done
done
change() { # $1 coarse, $2 fine: the fine value's change against the coarse one, %
  awk -v a="$1" -v b="$2" 'BEGIN { if (a == "" || b == "" || a !~ /^[-+0-9.eE]+$/ || b !~ /^[-+0-9.eE]+$/ || a == 0) print "-"; else printf "%+.1f %%", 100 * (b - a) / a }'
}
read -r -a ladder <<< "$levels"
if ((${#ladder[@]} > 1)); then
  echo "convergence (capacity, force at 1 cm; change from each level to the next finer one):"
  for height in $heights; do
    for ((l = 1; l < ${#ladder[@]}; ++l)); do
      coarse="reinforced_sand_H${height}_${ladder[l - 1]}" fine="reinforced_sand_H${height}_${ladder[l]}"
      echo "  H = $height m, ${ladder[l - 1]} -> ${ladder[l]}: capacity" \
        "$(change "${capacity[$coarse]:-}" "${capacity[$fine]:-}"), force at 1 cm" \
        "$(change "${force_1cm[$coarse]:-}" "${force_1cm[$fine]:-}")"
    done
  done
fi
