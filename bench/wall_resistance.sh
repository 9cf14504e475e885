#!/usr/bin/env bash
# Why the dynamic FEM's reinforced wall with its backfill resists about twice its static pushover
# (docs/validation.md "Yielding wall element against the dynamic FEM", "What the dynamic FEM's wall
# resists"). The reinforced 0.25 m wall of data/scenes/fem_reinforced_wall.yaml (H = 1.25 m,
# f_cm 38 MPa damaged concrete, bars rho_y 0.8 % / rho_x 0.2 % with the scene's strain
# penetration, crack spacing and tension stiffening, geostatic medium-dense sand; the numbers of
# docs/validation.md were measured with perfect bond, before the scene carried those keys),
# pushed in three ways and compared at the same band displacement:
#   - `kimp fem --pushover` (static, uniform band traction, IMPL-EX, 0.25 mm steps, to 40 mm);
#   - `kimp fem` with a rigid slab of 1e8 kg/m at 0.1 m/s (a displacement-controlled push in the
#     explicit impact solver: the slab loses < 1 % of its speed; 400 ms, 40 mm), on the impact
#     mesh of tests/e2e/yielding_wall_fem_test.cc (5 cm at the contact graded to 25 cm, ratio 1.5:
#     the wall's cells grow to 5 x 22 cm at its base), on a 5 -> 10 cm grading and on a uniform
#     5 cm mesh;
#   - with and without the backfill, with the concrete's tensile strength cut to 10 % (the section
#     analysis' assumption), with a frictional wall-sand contact instead of the bonded interface,
#     on a uniform 2.5 cm mesh (the bare wall), and with an elastic wall (stiffness).
# Prints the mean force over 10 mm windows of band displacement, the hand calculations (M_p / h_c
# of the smeared section, Rankine and Coulomb passive) and the CPU time of each run.
# KIMP_WALL_RESISTANCE_ROWS=1 also runs the four impact rows of the yielding-wall test (the FEM's
# 3.84 t/m slab and a rigid 55 t/m slab, 0.5 and 1 m/s) on the graded and the uniform mesh and
# prints the mean resistance of each by impulse-momentum (m v / t_stop) and energy (E0 / travel).
# About 3 minutes of CPU with the rows (one process at a time).
# Usage: bench/wall_resistance.sh [BUILD_DIR (default: build)]
set -euo pipefail
source "$(dirname "$0")/lib.sh"
bench_init wall_resistance.sh 1 "$@"
bench_require fem time
bench_workdir

# scene NAME CONCRETE(rc|rc_ft10|elastic) BACKFILL(true|false) MESH(graded|graded10|uniform|
#   uniform2.5) SLAB END [INTERFACE (default bonded)]
# (the impact rows keep the test's 0.01 ms history interval: their first peak is 0.1 ms long)
scene() {
  local concrete
  case "$2" in
    rc | rc_ft10)
      concrete="{model: damage_plasticity, f_cm: \"38 MPa\","
      [[ "$2" == rc_ft10 ]] && concrete+=" f_ctm: \"0.29 MPa\","
      concrete+=" wall_reinforcement: {ratio_y: \"0.8 %\", ratio_x: \"0.2 %\"},"
      concrete+=" slab_reinforcement: {ratio_x: \"0.5 %\"}}" ;;
    elastic) concrete="{model: elastic}" ;;
  esac
  local mesh
  case "$4" in
    graded) mesh='{h_contact: "5 cm", h_max: "25 cm", grading: 1.5}' ;;
    graded10) mesh='{h_contact: "5 cm", h_max: "10 cm", grading: 1.5}' ;;
    uniform) mesh='{h_contact: "5 cm", h_max: "5 cm", grading: 1.0}' ;;
    uniform2.5) mesh='{h_contact: "2.5 cm", h_max: "2.5 cm", grading: 1.0}' ;;
  esac
  local interval="0.5 ms"
  [[ "$1" == row_* ]] && interval="0.01 ms"
  cat > "$work/$1.yaml" <<YAML
wall_heights: ["1.25 m"]
geometry: {with_backfill: $3}
interface: {model: ${7:-bonded}}
materials:
  concrete: $concrete
  soil: {model: mohr_coulomb, preset: medium_dense_sand}
mesh: $mesh
slab: $5
dynamics: {end_time: "$6", output_interval: "$interval"}
output: {frame_interval: "0 ms"}
pushover: {displacement: "40 mm", increment: "0.25 mm"}
YAML
}

run() { # NAME [--pushover]
  local name="$1"
  shift
  if /usr/bin/time -f "%U" -o "$work/$name.cpu" "$kimp" fem "$work/$name.yaml" "$@" \
    -o "$work/$name" > /dev/null 2> "$work/$name.log"; then
    echo "$name: $(cat "$work/$name.cpu") s CPU"
  else
    echo "$name: failed: $(grep -m1 -i error "$work/$name.log" | cut -c1-160)"
  fi
}

push='{rigid: true, mass: "1e8 kg/m", velocity: "0.1 m/s"}'
scene pushover_soil rc true graded "$push" "400 ms"
scene pushover_bare rc false graded "$push" "400 ms"
scene pushover_bare_ft10 rc_ft10 false graded "$push" "400 ms"
scene pushover_elastic_soil elastic true graded "$push" "400 ms"
scene pushover_elastic_bare elastic false graded "$push" "400 ms"
for name in pushover_soil pushover_bare pushover_bare_ft10 pushover_elastic_soil \
  pushover_elastic_bare; do
  run "$name" --pushover
done
scene push_soil_graded rc true graded "$push" "400 ms"
scene push_soil_uniform rc true uniform "$push" "400 ms"
scene push_soil_uniform_contact rc true uniform "$push" "400 ms" contact
scene push_bare_graded rc false graded "$push" "400 ms"
scene push_bare_graded10 rc false graded10 "$push" "400 ms"
scene push_bare_uniform rc false uniform "$push" "400 ms"
scene push_bare_uniform2.5 rc false uniform2.5 "$push" "400 ms"
scene push_bare_ft10_graded rc_ft10 false graded "$push" "400 ms"
scene push_bare_ft10_uniform rc_ft10 false uniform "$push" "400 ms"
scene push_elastic_soil_graded elastic true graded "$push" "100 ms"
scene push_elastic_soil_uniform elastic true uniform "$push" "100 ms"
scene push_elastic_bare_graded elastic false graded "$push" "100 ms"
scene push_elastic_bare_uniform elastic false uniform "$push" "100 ms"
for name in push_soil_graded push_soil_uniform push_soil_uniform_contact push_bare_graded \
  push_bare_graded10 push_bare_uniform push_bare_uniform2.5 push_bare_ft10_graded \
  push_bare_ft10_uniform push_elastic_soil_graded push_elastic_soil_uniform \
  push_elastic_bare_graded push_elastic_bare_uniform; do
  run "$name"
done
rows=()
if [[ "${KIMP_WALL_RESISTANCE_ROWS:-0}" == 1 ]]; then
  for mesh in graded uniform; do
    for v in 0.5 1; do
      scene "row_fem_${v}_$mesh" rc true "$mesh" "{velocity: \"$v m/s\"}" "100 ms"
      scene "row_rigid_${v}_$mesh" rc true "$mesh" \
        "{velocity: \"$v m/s\", rigid: true, mass: \"55 t/m\"}" "400 ms"
      rows+=("row_fem_${v}_$mesh" "row_rigid_${v}_$mesh")
    done
  done
  for name in "${rows[@]}"; do
    run "$name"
  done
fi

python3 - "$work" "${rows[@]}" <<'PY'
import csv, math, os, sys
work, rows = sys.argv[1], sys.argv[2:]

def curve(name):
    """(band displacement m, force N/m): the pushover's curve or the push's band-mean history."""
    d = os.path.join(work, name)
    if name.startswith('pushover'):
        f = os.path.join(d, 'pushover.csv')
        if not os.path.exists(f): return None
        return [(float(r['displacement_m']), float(r['force_N_per_m'])) for r in csv.DictReader(open(f))]
    f = os.path.join(d, 'fem_histories.csv')
    if not os.path.exists(f): return None
    return [(float(r['wall_displacement_m']), float(r['smoothed_contact_force_N_per_m']))
            for r in csv.DictReader(open(f))]

def at(c, u):
    for (u0, f0), (u1, f1) in zip(c, c[1:]):
        if u1 >= u:
            return f0 + (f1 - f0) * (u - u0) / (u1 - u0) if u1 > u0 else f1
    return math.nan

def secant(c, u=0.005):
    return at(c, u) / u

# Hand calculations (SI).
t, H, fy, fcm, rho_y, g = 0.25, 1.25, 500e6, 38e6, 0.008, 9.80665
N = 2400 * g * t * H                                   # the wall's weight at its base
x = (rho_y * fy * t - N) / (0.68 * fcm + 2 * rho_y * fy)  # smeared bars, both sides yielding
T, C, Cs = rho_y * fy * (t - x), 0.68 * fcm * x, rho_y * fy * x
Mp = T * ((t + x) / 2 - t / 2) + C * (t / 2 - 0.4 * x) + Cs * (t / 2 - x / 2)
phi, gam = math.radians(34), 1850 * g
Kp = (1 + math.sin(phi)) / (1 - math.sin(phi))
d = 2 * phi / 3
Kpc = math.cos(phi)**2 / (math.cos(d) * (1 - math.sqrt(math.sin(phi + d) * math.sin(phi) / math.cos(d)))**2)
Pp, Ppc = 0.5 * Kp * gam * H**2, 0.5 * Kpc * gam * H**2 * math.cos(d)
print(f"\nhand: smeared section (rho_y 0.8 %, f_y 500 MPa, block 0.85 f_cm over 0.8x, N {N/1e3:.2f} kN/m): "
      f"x {x*1e3:.1f} mm, M_p {Mp/1e3:.1f} kNm/m; M_p / 1.15 m (band resultant) {Mp/1.15/1e3:.1f} kN/m, "
      f"M_p / 1.05 m (band's lower edge) {Mp/1.05/1e3:.1f} kN/m")
print(f"hand: passive, phi 34 deg, gamma {gam/1e3:.2f} kN/m3: Rankine {Pp/1e3:.1f} kN/m, Coulomb (delta 2phi/3, "
      f"horizontal) {Ppc/1e3:.1f} kN/m; at H/3 on a wall rotating about its base, at the band (1.05-1.15 m): "
      f"{Pp*H/3/1.15/1e3:.1f}-{Pp*H/3/1.05/1e3:.1f} (Rankine), {Ppc*H/3/1.15/1e3:.1f}-{Ppc*H/3/1.05/1e3:.1f} kN/m (Coulomb)")

def window(c, a, b):
    if max(u for u, _ in c) < 0.99 * b:
        return math.nan  # the push ends before the window does
    fs = [f for u, f in c if a <= u < b]
    return sum(fs) / len(fs) if fs else math.nan

print("\nmean force (kN/m) over band-displacement windows (the explicit pushes drop and recover as")
print("cracks and crushing pass a row); secant stiffness at 5 mm (kN/mm/m)")
print(f"{'case':28s} {'0-10 mm':>8s} {'10-20':>8s} {'20-30':>8s} {'30-40':>8s} {'k(5mm)':>8s}")
for name in ['pushover_soil', 'push_soil_graded', 'push_soil_uniform', 'push_soil_uniform_contact',
             'pushover_bare', 'push_bare_graded', 'push_bare_graded10', 'push_bare_uniform',
             'push_bare_uniform2.5', 'pushover_bare_ft10', 'push_bare_ft10_graded',
             'push_bare_ft10_uniform', 'pushover_elastic_soil', 'push_elastic_soil_graded',
             'push_elastic_soil_uniform', 'pushover_elastic_bare', 'push_elastic_bare_graded',
             'push_elastic_bare_uniform']:
    c = curve(name)
    if not c:
        print(f"{name:28s} (no result)"); continue
    vals = [window(c, a * 1e-3, (a + 10) * 1e-3) / 1e3 for a in (0, 10, 20, 30)]
    print(f"{name:28s} " + " ".join(f"{v:8.1f}" for v in vals) + f" {secant(c)/1e6:8.2f}")

if rows:
    print("\nimpact rows (the yielding-wall test's quantities) and the mean resistance")
    for name in rows:
        f = os.path.join(work, name, 'fem_histories.csv')
        if not os.path.exists(f):
            print(f"{name}: no result"); continue
        m = 55e3 if 'rigid' in name else 3840.0
        v0 = float(name.split('_')[2])
        x = 0.0; touch = None; tp = vp = 0.0; stop = None; peak = 0.0; xmax = 0.0; wall = 0.0
        for r in csv.DictReader(open(f)):
            tt, ff, v = float(r['time_s']), float(r['smoothed_contact_force_N_per_m']), float(r['slab_velocity_m_per_s'])
            if touch is not None: x += 0.5 * (v + vp) * (tt - tp)
            elif ff > 0: touch = tt
            if touch is not None and stop is None and v <= 0: stop = tt - touch
            peak, xmax, wall, tp, vp = max(peak, ff), max(xmax, x), float(r['wall_displacement_m']), tt, v
        mv = m * v0 / stop / 1e3 if stop else math.nan
        print(f"{name:22s} peak {peak/1e3:7.1f} kN/m, slab travel {xmax*1e3:7.2f} mm, time to stop "
              f"{stop*1e3 if stop else math.nan:6.1f} ms, wall at the end {wall*1e3:7.2f} mm; "
              f"m v / t_stop {mv:6.1f}, E0 / travel {0.5*m*v0*v0/xmax/1e3:6.1f} kN/m")
PY
