#!/usr/bin/python3
"""Directionality study in plan (docs/validation.md "Pounding in plan"): `kimp lumped` of a plan
scene (default data/scenes/plan_4storey_moat.yaml) with plan.angle over 0-180 degrees, the mass
eccentricity along x over fractions of the plan width and one component of each motion turned to
each angle. Writes OUT/directionality.csv (one row per run, the peaks of its summary.json),
OUT/directionality_<motion>.png and .svg (peaks against angle, one line per eccentricity) and
OUT/directionality.md (the table), each under a temporary name renamed when complete.

usage: plan_directionality.py --kimp BUILD/kimp --out DIR [--scene S.yaml] [--records-dir D]
       [--motions RSN1106_KOBE_KJM000,SCS142,synthetic] [--eccentricities 0,5,10]
       [--angles 0:180:15] [--duration 48] [--jobs 2]"""
import argparse
import concurrent.futures
import csv
import json
import os
import subprocess
import sys

import yaml

PEAKS = [("base_corner_displacement", "peak base corner displacement", "cm", 100.0),
         ("corner_impact_force", "peak corner impact force", "MN", 1e-6),
         ("top_acceleration", "top-floor acceleration", "g", 1.0 / 9.80665),
         ("corner_drift", "peak corner drift", "mm", 1000.0),
         ("rotation", "peak rotation", "mrad", 1000.0)]


def atomic_write(path, write):
    tmp = path + ".tmp"
    write(tmp)
    os.replace(tmp, path)


def run_one(args, scene, motion, ecc, angle):
    name = f"{motion}_e{ecc:g}_a{angle:g}"
    work = os.path.join(args.out, "runs", name)
    os.makedirs(work, exist_ok=True)
    s = json.loads(json.dumps(scene))
    s.setdefault("ground_motion", {})["record"] = motion
    if motion == "synthetic":
        s["ground_motion"].pop("duration", None)  # the synthetic motion's own 20 s
    if args.duration:
        s["ground_motion"]["duration"] = f"{args.duration} s"
    p = s.setdefault("plan", {})
    width = float(str(p.get("width", "20 m")).split()[0])
    p["eccentricity_x"] = f"{ecc / 100.0 * width} m"
    p["eccentricity_y"] = "0 m"
    p["angle"] = angle
    p["second_component"] = "none"
    s.setdefault("integration", {})["output_interval"] = "0 s"
    scene_file = os.path.join(work, "scene.yaml")
    text = yaml.safe_dump(s, sort_keys=False)
    out = os.path.join(work, "out")
    summary_file = os.path.join(out, "summary.json")
    # A run of the same scene text already complete (an interrupted study resumed) is reused.
    reuse = os.path.exists(summary_file) and os.path.exists(scene_file) and \
        open(scene_file).read() == text
    if not reuse:
        with open(scene_file, "w") as f:
            f.write(text)
        run_kimp(args, scene_file, out, name)
    with open(summary_file) as f:
        summary = json.load(f)
    return row_of(motion, ecc, angle, summary)


def run_kimp(args, scene_file, out, name):
    command = [args.kimp, "--quiet", "lumped", scene_file, "-o", out]
    if args.records_dir:
        command += ["--records-dir", args.records_dir]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{name}: kimp exited {done.returncode}: {done.stderr.strip()}")


def row_of(motion, ecc, angle, summary):
    case = summary["cases"][0]
    row = {"motion": motion, "eccentricity_percent": ecc, "angle_deg": angle,
           "n_impacts": case["n_impacts"],
           "energy_max_relative_error": case["energy"]["max_relative_error"],
           "friction_work_J": case["energy"]["friction"]}
    for key, _, _, _ in PEAKS:
        row[key] = case["peaks"][key]
    return row


def chart(rows, motion, path_stem):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
    for ax, (key, label, unit, factor) in zip(axes.flat, PEAKS[:4]):
        for ecc in sorted({r["eccentricity_percent"] for r in rows}):
            rs = sorted((r for r in rows if r["eccentricity_percent"] == ecc),
                        key=lambda r: r["angle_deg"])
            ax.plot([r["angle_deg"] for r in rs], [r[key] * factor for r in rs], "o-",
                    label=f"e = {ecc:g} % of the width")
        ax.set_ylabel(f"{label} [{unit}]")
        ax.set_xticks(range(0, 181, 30))
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("angle of incidence [deg from x]")
    axes[0][0].legend(fontsize=8)
    fig.suptitle(f"Directionality in plan: {motion}")
    fig.tight_layout()
    for ext in ("png", "svg"):
        atomic_write(f"{path_stem}.{ext}", lambda tmp: fig.savefig(tmp, format=ext, dpi=110))
    plt.close(fig)


def table(rows):
    lines = ["| motion | e [%] | angle [deg] | base corner disp. [cm] | corner impact force [MN] "
             "| top acc. [g] | corner drift [mm] | rotation [mrad] | impacts |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        cells = [r["motion"], f"{r['eccentricity_percent']:g}", f"{r['angle_deg']:g}"]
        cells += [f"{r[key] * factor:.3g}" for key, _, _, factor in PEAKS]
        cells.append(str(r["n_impacts"]))
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser.add_argument("--kimp", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--scene", default=os.path.join(root, "data/scenes/plan_4storey_moat.yaml"))
    parser.add_argument("--records-dir", default="")
    parser.add_argument("--motions", default="RSN1106_KOBE_KJM000,SCS142,synthetic")
    parser.add_argument("--eccentricities", default="0,5,10")
    parser.add_argument("--angles", default="0:180:15")
    parser.add_argument("--duration", type=float, default=0.0,
                        help="seconds of each motion (0: the scene's)")
    parser.add_argument("--jobs", type=int, default=1)
    args = parser.parse_args()
    args.kimp = os.path.abspath(args.kimp)
    with open(args.scene) as f:
        scene = yaml.safe_load(f)
    first, last, step = (float(v) for v in args.angles.split(":"))
    angles = []
    a = first
    while a <= last + 1e-9:
        angles.append(a)
        a += step
    eccs = [float(v) for v in args.eccentricities.split(",")]
    motions = args.motions.split(",")
    os.makedirs(args.out, exist_ok=True)
    jobs = [(m, e, a) for m in motions for e in eccs for a in angles]
    rows = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(run_one, args, scene, m, e, a) for m, e, a in jobs]
        for future in futures:
            rows.append(future.result())
            r = rows[-1]
            print(f"{r['motion']} e={r['eccentricity_percent']:g}% angle={r['angle_deg']:g}: "
                  f"base {r['base_corner_displacement'] * 100:.3g} cm, force "
                  f"{r['corner_impact_force'] / 1e6:.3g} MN", file=sys.stderr, flush=True)
    fields = list(rows[0].keys())

    def write_csv(tmp):
        with open(tmp, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields)
            w.writeheader()
            w.writerows(rows)

    atomic_write(os.path.join(args.out, "directionality.csv"), write_csv)
    for m in motions:
        chart([r for r in rows if r["motion"] == m], m,
              os.path.join(args.out, f"directionality_{m}"))

    def write_md(tmp):
        with open(tmp, "w") as f:
            f.write(table(rows))

    atomic_write(os.path.join(args.out, "directionality.md"), write_md)


if __name__ == "__main__":
    main()
