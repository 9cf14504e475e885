#!/usr/bin/python3
"""Charts of `kimp study DIR`: FEM contact force with the fitted laws (one panel per wall height),
k against wall height beside thesis Table 2.1 (fit interval and FEM numerical error), k against
impact velocity per wall height (with the linear k beside an inelastic one), building
response against wall height and, when the study computed them, accuracy against cost (FEM levels;
building time step), the central-difference stability map and the sensitivity of k.
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
            unit = "kN/mm/m" if n == 1 else f"kN/mm$^{{{n:g}}}$/m"
            ax.plot(t, fit["model_force"][()] / 1e3, style, lw=1.5,
                    label=f"{law.replace('_', '-')}: k = {k_display:.4g} {unit}")
        ax.set_title(f"H = {case[1:]} m")
        ax.set_xlabel("time since first contact (ms)")
        ax.set_ylabel("contact force (kN/m)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    save(fig, out_dir, "force_histories")


def k_vs_height(h5, out_dir):
    table = h5["k_table"]
    h = table["wall_height"][()]
    if len(set(h)) < 2:
        return  # one height (a site): one point, the report's k table says it
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
    for ax, law, unit in ((axes[0], "kelvin_voigt", "kN/mm/m"), (axes[1], "jankowski", "kN/mm^1.5/m")):
        k = table[law][()]
        lower = table[law + "_lower"][()]
        upper = table[law + "_upper"][()]
        err = [[max(a - b, 0.0) for a, b in zip(k, lower)], [max(b - a, 0.0) for a, b in zip(k, upper)]]
        ax.errorbar(h, k, yerr=err, fmt="o-", capsize=3, label="kimp (fit 95 % CI)")
        shown = list(k) + list(lower) + list(upper)
        if law + "_numerical_error" in table:
            num = table[law + "_numerical_error"][()]
            if any(not math.isnan(x) for x in num):
                num = [0.0 if math.isnan(x) else x for x in num]
                ax.errorbar(h, k, yerr=num, fmt="none", elinewidth=4, alpha=0.4, color="C3",
                            label="FEM numerical error (level change)")
        thesis = table["thesis_" + law][()]
        points = [(a, b) for a, b in zip(h, thesis) if not math.isnan(b)]
        if points:
            ax.plot([p[0] for p in points], [p[1] for p in points], "s--", label="thesis Table 2.1")
            shown += [p[1] for p in points]
        value_axis(ax, "y", shown)
        if len(set(h)) == 1:  # one height: a readable x axis around it, the value written
            ax.set_xlim(h[0] - 0.5, h[0] + 0.5)
            if not math.isnan(k[0]):
                ax.annotate(f"{k[0]:.4g} [{lower[0]:.4g}, {upper[0]:.4g}]", (h[0], k[0]),
                            xytext=(8, 0), textcoords="offset points", va="center", fontsize=8)
        ax.set_xlabel("wall height H (m)")
        ax.set_ylabel(f"k ({unit_text(unit)})")
        ax.set_title(law.replace("_", "-"))
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    save(fig, out_dir, "k_vs_height")


def k_vs_velocity(h5, out_dir):
    """k against impact velocity, one line per wall height (fit 95 % interval as error bars), with
    the linear-elastic k dashed where the FEM was inelastic."""
    if "k_table_velocity" not in h5:
        return
    table = h5["k_table_velocity"]
    h = table["wall_height"][()]
    v = table["impact_velocity"][()]
    if len(set(v)) < 2:
        return
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
    for ax, law, unit in ((axes[0], "kelvin_voigt", "kN/mm/m"), (axes[1], "jankowski", "kN/mm^1.5/m")):
        k = table[law][()]
        lower = table[law + "_lower"][()]
        upper = table[law + "_upper"][()]
        linear = table["linear_" + law][()]
        for i, height in enumerate(sorted(set(h))):
            rows = sorted((v[j], k[j], lower[j], upper[j], linear[j]) for j in range(len(h))
                          if h[j] == height and not math.isnan(k[j]))
            if not rows:
                continue
            xs = [r[0] for r in rows]
            ys = [r[1] for r in rows]
            err = [[max(r[1] - r[2], 0.0) for r in rows], [max(r[3] - r[1], 0.0) for r in rows]]
            ax.errorbar(xs, ys, yerr=err, fmt="o-", capsize=3, color=f"C{i}", label=f"H = {height:g} m")
            lin = [(r[0], r[4]) for r in rows if not math.isnan(r[4])]
            if lin:
                ax.plot([p[0] for p in lin], [p[1] for p in lin], "--", color=f"C{i}",
                        label=f"H = {height:g} m, linear")
        valid = [j for j in range(len(h)) if not math.isnan(k[j])]
        value_axis(ax, "x", [v[j] for j in valid])
        value_axis(ax, "y", [k[j] for j in valid] + [lower[j] for j in valid]
                   + [upper[j] for j in valid] + [x for x in linear if not math.isnan(x)])
        ax.set_xlabel("impact velocity v (m/s)")
        ax.set_ylabel(f"k ({unit_text(unit)})")
        ax.set_title(law.replace("_", "-"))
        ax.grid(alpha=0.3, which="both")
    # One legend beside both panels: inside, it covered the lines of the stiffest wall.
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="center left", bbox_to_anchor=(1.0, 0.5), fontsize=8)
    save(fig, out_dir, "k_vs_velocity")


def building_response(csv_path, out_dir):
    """Peak responses against wall height, one line per law, the run without walls dotted. With
    one wall height (a site's study), bars per law with their values instead."""
    with open(csv_path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["status"] == "ok"]
    quantities = (("peak_top_acceleration_m_per_s2", "peak top abs. acceleration (m/s²)"),
                  ("peak_interstorey_drift_cm", "peak interstorey drift (cm)"),
                  ("peak_impact_force_kN", "peak impact force (MN)"))
    scale = {"peak_impact_force_kN": 1e-3}  # kN -> MN: tens of MN read better than 38950 kN
    laws = ("modified_kelvin_voigt", "jankowski", "hysteretic")
    records = sorted({r["record"] for r in rows})
    heights = sorted({float(r["wall_height_m"]) for r in rows if r["law"] != "none"})
    fig, axes = plt.subplots(len(records), len(quantities), figsize=(12, 3.4 * len(records)),
                             constrained_layout=True, squeeze=False)
    for i, record in enumerate(records):
        mine = [r for r in rows if r["record"] == record]
        bare = [r for r in mine if r["law"] == "none"]
        for j, (key, label) in enumerate(quantities):
            ax = axes[i][j]
            if len(heights) == 1:
                names, values, colours = [], [], []
                if bare and key != "peak_impact_force_kN":
                    names.append("no walls")
                    values.append(float(bare[0][key]) * scale.get(key, 1.0))
                    colours.append("0.6")
                for k, law in enumerate(laws):
                    v = [float(r[key]) * scale.get(key, 1.0) for r in mine if r["law"] == law]
                    if v:
                        names.append(law.replace("_", " ").replace("modified ", "mod. "))
                        values.append(v[0])
                        colours.append(f"C{k}")
                bars = ax.bar(range(len(names)), values, color=colours)
                ax.bar_label(bars, labels=[f"{v:.4g}" if abs(v) < 1e4 else f"{v:.0f}"
                                           for v in values], fontsize=8)
                ax.set_xticks(range(len(names)))
                ax.set_xticklabels(names, fontsize=8)
                ax.set_ylim(0, 1.15 * max(values) if values else 1)
                ax.set_title(f"{record}, H = {heights[0]:g} m", fontsize=9)
                ax.set_ylabel(label)
                ax.grid(alpha=0.3, axis="y")
                continue
            for law in laws:
                pts = sorted((float(r["wall_height_m"]), float(r[key]) * scale.get(key, 1.0))
                             for r in mine if r["law"] == law)
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


def plain_log_ticks(axis):
    """Plain numbers on a log axis ("57.5", not "5.75×10^1"). Minor ticks are labelled only where
    the labels fit: at 2, 3 and 5 times a power of ten over about a decade, at 2 and 5 over up to
    2.5 decades, not at all over more."""
    from matplotlib import ticker

    def plain(value, _):
        return f"{value:g}"

    def minor(value, _):
        lo, hi = sorted(axis.get_view_interval())
        if value <= 0 or lo <= 0:
            return ""
        decades = math.log10(hi / lo)
        labelled = (2.0, 3.0, 5.0) if decades <= 1.2 else (2.0, 5.0) if decades <= 2.5 else ()
        leading = value / 10 ** math.floor(math.log10(value) + 1e-9)
        return f"{value:g}" if round(leading, 6) in labelled else ""

    axis.set_major_formatter(ticker.FuncFormatter(plain))
    axis.set_minor_formatter(ticker.FuncFormatter(minor))


def value_axis(ax, which, values):
    """A log axis (plain tick labels) when the values span a factor of 3 or more, else a linear
    axis with plain numbers: a log axis over a narrow range has no labelled tick at all."""
    positive = [v for v in values if v is not None and math.isfinite(v) and v > 0]
    axis = ax.yaxis if which == "y" else ax.xaxis
    if positive and max(positive) / min(positive) >= 3.0:
        (ax.set_yscale if which == "y" else ax.set_xscale)("log")
        plain_log_ticks(axis)
        return
    from matplotlib import ticker
    formatter = ticker.ScalarFormatter(useOffset=False)
    formatter.set_scientific(False)
    axis.set_major_formatter(formatter)
    if positive:  # some room around a single value
        lo, hi = min(positive), max(positive)
        pad = 0.15 * (hi - lo) if hi > lo else 0.1 * hi
        (ax.set_ylim if which == "y" else ax.set_xlim)(max(0.0, lo - pad), hi + pad)


def unit_text(unit):
    """A unit in math text: "kN/mm^1.5/m" -> "kN/mm$^{1.5}$/m"."""
    return unit.replace("^1.5", "$^{1.5}$")


def log_log_axes(ax, xlabel, ylabel, title):
    """Log-log axes with labels, title, grid and a small legend (the accuracy and stability charts)."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain_log_ticks(ax.xaxis)
    plain_log_ticks(ax.yaxis)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)


def accuracy_fem(h5, out_dir):
    """Error of k against the finest explicit level, against FEM wall time. The reference run
    itself (error 0, no place on a log axis) is a star on the bottom edge."""
    if "accuracy" not in h5 or "fem" not in h5["accuracy"]:
        return
    group = h5["accuracy"]["fem"]
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), constrained_layout=True)
    # series: (style, legend, label of a point, label offset in points)
    styles = {"mesh": ("o-", "explicit, mesh levels (label: contact cell)",
                       lambda hc, pf: f"{hc * 100:g} cm", (4, 4)),
              "penalty": ("s--", "explicit, penalty levels (label: factor)",
                          lambda hc, pf: f"×{pf:g}", (4, -10)),
              "implicit": ("^:", "implicit Newmark, mesh levels",
                           lambda hc, pf: f"{hc * 100:g} cm", (-28, 4))}
    for ax, law, title in ((axes[0], "kelvin_voigt", "Kelvin-Voigt k"),
                           (axes[1], "jankowski", "Jankowski k")):
        references = []
        for series, (style, label, tag, offset) in styles.items():
            if series not in group:
                continue
            t = group[series]
            ok = t["ok"][()]
            sec = t["seconds"][()]
            err = t["error_" + law][()]
            pts = [(s_, e * 100, hc, pf) for s_, e, o, hc, pf in
                   zip(sec, err, ok, t["h_contact"][()], t["penalty_factor"][()]) if o > 0.5]
            drawn = [p for p in pts if p[1] > 0]
            references += [p for p in pts if p[1] <= 0]
            if drawn:
                ax.plot([p[0] for p in drawn], [p[1] for p in drawn], style, label=label)
                for p in drawn:
                    ax.annotate(tag(p[2], p[3]), (p[0], p[1]), fontsize=7, xytext=offset,
                                textcoords="offset points")
            failed = [s_ for s_, o in zip(sec, ok) if o < 0.5]
            for f in failed:
                ax.axvline(f if f > 0 else 1e-3, color="r", ls=":", lw=0.8)
        log_log_axes(ax, "FEM wall time (s)", r"$|k/k_\mathrm{finest} - 1|$ (%)", title)
        if references:
            bottom = ax.get_ylim()[0]
            ax.plot([p[0] for p in references], [bottom] * len(references), "*", ms=11,
                    color="k", clip_on=False, zorder=5,
                    label=r"reference $k_\mathrm{finest}$ (error 0)")
            for p in references:
                ax.annotate(f"{p[2] * 100:g} cm, ×{p[3]:g}", (p[0], bottom), fontsize=7,
                            xytext=(6, 4), textcoords="offset points")
            ax.set_ylim(bottom=bottom)
        ax.get_legend().remove()
    # One legend for both panels, below them (inside, it hid the points and their labels).
    handles, labels = axes[1].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2, fontsize=8)
    save(fig, out_dir, "accuracy_fem")


def accuracy_lumped(h5, out_dir):
    if "accuracy" not in h5 or "lumped" not in h5["accuracy"]:
        return
    group = h5["accuracy"]["lumped"]
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), constrained_layout=True)
    for ax, key, title in ((axes[0], "error_impact_force", "peak impact force"),
                           (axes[1], "error_base_acceleration", "peak base abs. acceleration")):
        for method, style, label in (("cdm", "o-", "central difference"),
                                     ("newmark", "s--", "Newmark (average acceleration)")):
            if method not in group:
                continue
            t = group[method]
            pts = [(s_, max(e, 1e-7) * 100, dt) for s_, e, o, dt in
                   zip(t["seconds"][()], t[key][()], t["ok"][()], t["dt"][()]) if o > 0.5]
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], style, label=label)
                for p in pts:
                    ax.annotate(f"{p[2] * 1e3:g} ms", (p[0], p[1]), fontsize=6, xytext=(3, 3),
                                textcoords="offset points")
        log_log_axes(ax, "wall time of the run (s); labels: time step Δt", "error vs reference (%)",
                     title)
    save(fig, out_dir, "accuracy_lumped")


def stability_map(h5, out_dir):
    if "stability" not in h5 or "lumped" not in h5["stability"]:
        return
    t = h5["stability"]["lumped"]
    k = t["stiffness"][()] * 1e-6  # kN/mm
    dt = t["dt"][()]
    stable = t["stable"][()]
    accurate = t["accurate"][()] if "accurate" in t else stable
    fig, ax = plt.subplots(figsize=(8.5, 4.2), constrained_layout=True)
    for sel, marker, color, label in (
            (lambda i: accurate[i] > 0.5, "o", "C2", "stable, COR within 5 %"),
            (lambda i: stable[i] > 0.5 and accurate[i] < 0.5, "s", "C1", "stable, inaccurate"),
            (lambda i: stable[i] < 0.5, "x", "C3", "unstable (energy gained)")):
        idx = [i for i in range(len(k)) if sel(i)]
        if idx:
            ax.scatter([k[i] for i in idx], [dt[i] for i in idx], marker=marker, color=color, s=14,
                       label=label)
    order = sorted(range(len(k)), key=lambda i: k[i])
    ks = [k[i] for i in order]
    ax.plot(ks, [t["dt_limit"][()][i] for i in order], "k-", label=r"$2/\omega_\mathrm{imp}$")
    ax.plot(ks, [t["dt_limit_damped"][()][i] for i in order], "k--",
            label=r"$2(\sqrt{1+\xi^2}-\xi)/\omega_\mathrm{imp}$ (KV dashpot)")
    k_study = t.attrs.get("study_stiffness_N_per_m", None)
    if k_study:
        ax.axvline(float(k_study) * 1e-6, color="C0", ls=":", label=r"study $k_\mathrm{KV}$ (total)")
    log_log_axes(ax, r"$k_\mathrm{imp}$ (kN/mm)", r"time step $\Delta t$ (s)", "central difference, two-body contact")
    # Time steps far above the limit are all unstable and say nothing more: show up to 30 times
    # the largest limit, and keep the legend off the points.
    limits = [v for v in t["dt_limit"][()] if math.isfinite(v) and v > 0]
    if limits:
        ax.set_ylim(top=min(ax.get_ylim()[1], 30 * max(limits)))
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    save(fig, out_dir, "stability_map")


def stability_map_fem(h5, out_dir):
    if "stability" not in h5 or "fem" not in h5["stability"]:
        return
    t = h5["stability"]["fem"]
    penalty = t["penalty_factor"][()]
    dt = t["dt"][()] * 1e6
    stable = t["stable"][()]
    fig, ax = plt.subplots(figsize=(6, 4.2), constrained_layout=True)
    for want, marker, color, label in ((1, "o", "C2", "stable"),
                                       (0, "x", "C3", "unstable (diverged or energy error > 1 %)")):
        idx = [i for i in range(len(dt)) if (stable[i] > 0.5) == bool(want) and math.isfinite(dt[i])]
        if idx:
            ax.scatter([penalty[i] for i in idx], [dt[i] for i in idx], marker=marker, color=color,
                       s=24, label=label)
    limits = {}
    for p, lim in zip(penalty, t["dt_limit"][()]):
        if math.isfinite(lim):
            limits[float(p)] = lim * 1e6
    if limits:
        ps = sorted(limits)
        ax.plot(ps, [limits[p] for p in ps], "k-", label=r"computed limit $2(\sqrt{1+\xi^2}-\xi)/\omega$")
    h = t.attrs.get("h_contact_m", None)
    log_log_axes(ax, "penalty factor (× E/h)", r"time step $\Delta t$ (μs)",
                 "explicit FEM" + (f", {float(h) * 100:g} cm contact elements" if h else ""))
    save(fig, out_dir, "stability_map_fem")


def sensitivity(h5, out_dir):
    if "sensitivity" not in h5:
        return
    g = h5["sensitivity"]
    base = g["base"]
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6), constrained_layout=True)
    names = [n for n in ("soil_modulus", "slab_mass", "impact_velocity", "wall_thickness") if n in g]
    for ax, law in ((axes[0], "kelvin_voigt"), (axes[1], "jankowski")):
        k0 = base[law][()][0]
        for i, name in enumerate(names):
            t = g[name]
            for f, k in zip(t["factor"][()], t[law][()]):
                if math.isnan(k) or math.isnan(k0):
                    continue
                change = (k / k0 - 1) * 100
                ax.barh(i, change, color="C0" if f < 1 else "C1", alpha=0.8,
                        label=("-" if f < 1 else "+") + f"{abs(f - 1) * 100:g} %" if i == 0 else None)
        ax.axvline(0, color="k", lw=0.8)
        ax.set_yticks(range(len(names)))
        ax.set_yticklabels([n.replace("_", " ") for n in names])
        ax.set_xlabel(f"change of k ({law.replace('_', '-')}) (%)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    save(fig, out_dir, "sensitivity")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: study_charts.py DIR (the output directory of kimp study)")
    directory = sys.argv[1]
    out_dir = os.path.join(directory, "charts")
    os.makedirs(out_dir, exist_ok=True)
    with h5py.File(os.path.join(directory, "study.h5"), "r") as h5:
        force_histories(h5, out_dir)
        k_vs_height(h5, out_dir)
        k_vs_velocity(h5, out_dir)
        accuracy_fem(h5, out_dir)
        accuracy_lumped(h5, out_dir)
        stability_map(h5, out_dir)
        stability_map_fem(h5, out_dir)
        sensitivity(h5, out_dir)
    building_response(os.path.join(directory, "building_response.csv"), out_dir)


if __name__ == "__main__":
    main()
