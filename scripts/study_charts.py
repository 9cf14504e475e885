#!/usr/bin/python3
"""Charts of `kimp study DIR`: FEM contact force with the fitted laws (one panel per wall height),
k against wall height beside thesis Table 2.1, and building response against wall height.
Reads DIR/study.h5 and DIR/building_response.csv; writes DIR/charts/*.png and *.svg."""
import csv
import math
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def save(fig, out_dir, name):
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out_dir, f"{name}.{ext}"), dpi=130, bbox_inches="tight")
    plt.close(fig)


def force_histories(h5, out_dir):
    cases = sorted(h5["fit"].keys(), key=lambda c: float(h5["fit"][c]["wall_height"][()]))
    fig, axes = plt.subplots(1, len(cases), figsize=(4.0 * len(cases), 3.4), squeeze=False,
                             constrained_layout=True)
    for ax, case in zip(axes[0], cases):
        group = h5["fit"][case]
        drawn_fem = False
        for law, style in (("kelvin_voigt", "--"), ("jankowski", ":")):
            if law not in group or "time" not in group[law]:
                continue
            fit = group[law]
            t = (fit["time"][()] - fit["time"][0]) * 1e3
            if not drawn_fem:
                ax.plot(t, fit["fem_force"][()] / 1e3, "k-", lw=1.5, label="FEM")
                drawn_fem = True
            k = fit["stiffness"][()]
            n = fit["exponent"][()]
            k_display = k * 1e-3 ** (n + 1)
            unit = "kN/mm/m" if n == 1 else f"kN/mm^{n:g}/m"
            ax.plot(t, fit["model_force"][()] / 1e3, style, lw=1.5,
                    label=f"{law.replace('_', '-')} k = {k_display:.3g} {unit}")
        ax.set_title(f"H = {case[1:]} m")
        ax.set_xlabel("time since first contact (ms)")
        ax.set_ylabel("contact force (kN/m)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    save(fig, out_dir, "force_histories")


def k_vs_height(h5, out_dir):
    table = h5["k_table"]
    h = table["wall_height"][()]
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
    for ax, law, unit in ((axes[0], "kelvin_voigt", "kN/mm/m"), (axes[1], "jankowski", "kN/mm^1.5/m")):
        k = table[law][()]
        lower = table[law + "_lower"][()]
        upper = table[law + "_upper"][()]
        err = [[max(a - b, 0.0) for a, b in zip(k, lower)], [max(b - a, 0.0) for a, b in zip(k, upper)]]
        ax.errorbar(h, k, yerr=err, fmt="o-", capsize=3, label="kimp (fit 95 % CI)")
        thesis = table["thesis_" + law][()]
        points = [(a, b) for a, b in zip(h, thesis) if not math.isnan(b)]
        if points:
            ax.plot([p[0] for p in points], [p[1] for p in points], "s--", label="thesis Table 2.1")
        ax.set_yscale("log")
        ax.set_xlabel("wall height H (m)")
        ax.set_ylabel(f"k ({unit})")
        ax.set_title(law.replace("_", "-"))
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    save(fig, out_dir, "k_vs_height")


def building_response(csv_path, out_dir):
    with open(csv_path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["status"] == "ok"]
    quantities = (("peak_top_acceleration_m_per_s2", "peak top abs. acceleration (m/s²)"),
                  ("peak_interstorey_drift_cm", "peak interstorey drift (cm)"),
                  ("peak_impact_force_kN", "peak impact force (kN)"))
    records = sorted({r["record"] for r in rows})
    fig, axes = plt.subplots(len(records), len(quantities), figsize=(12, 3.4 * len(records)),
                             constrained_layout=True, squeeze=False)
    for i, record in enumerate(records):
        mine = [r for r in rows if r["record"] == record]
        bare = [r for r in mine if r["law"] == "none"]
        for j, (key, label) in enumerate(quantities):
            ax = axes[i][j]
            for law in ("modified_kelvin_voigt", "jankowski", "hysteretic"):
                pts = sorted((float(r["wall_height_m"]), float(r[key])) for r in mine if r["law"] == law)
                if pts:
                    ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=law.replace("_", " "))
            if bare and key != "peak_impact_force_kN":
                ax.axhline(float(bare[0][key]), color="k", ls=":", label="no walls")
            ax.set_xlabel("wall height H (m)")
            ax.set_ylabel(label)
            ax.set_title(record, fontsize=9)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
    save(fig, out_dir, "building_response")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: study_charts.py DIR (the output directory of kimp study)")
    directory = sys.argv[1]
    out_dir = os.path.join(directory, "charts")
    os.makedirs(out_dir, exist_ok=True)
    with h5py.File(os.path.join(directory, "study.h5"), "r") as h5:
        force_histories(h5, out_dir)
        k_vs_height(h5, out_dir)
    building_response(os.path.join(directory, "building_response.csv"), out_dir)


if __name__ == "__main__":
    main()
