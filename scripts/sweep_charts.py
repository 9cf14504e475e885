#!/usr/bin/python3
"""Charts and summary.md of `kimp sweep SWEEP.yaml -o DIR` (studies 1-6 of data/studies).
Reads DIR/sweep.csv, the plan JSON in DIR/sweep.h5 (/input/resolved: parameters, their settings and
the `report:` section) and DIR/dsrss_table.csv if present; writes DIR/charts/*.png and *.svg and
DIR/summary.md, each under a temporary name renamed when complete. Every number comes from the data.
The input is read by sweep_data.py, the chart building blocks are in sweep_plots.py; this file holds
the charts of each report kind, the d_SRSS table and the summary."""
import math
import os
import re
import sys
import traceback

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

from sweep_data import MAIN_BUILDING, NAN, Sweep, axis_name, fmt, number, quantity
from sweep_plots import (AMPLIFICATIONS, PEAK_FORCE, RESPONSES, describe, gap_charts, other_params,
                         panels_vs, property_charts, save, shown)

# ---------------------------------------------------------------------------------------- kinds
# Peaks of a sweep of scenes in plan (the metric names of kimp's plan rows).
PLAN_RESPONSES = [
    ("base_corner_displacement", "peak base corner displacement [cm]",
     lambda s, r: 100 * s.value(r, "base_corner_displacement [m]")),
    ("corner_impact_force", "peak corner impact force [MN]",
     lambda s, r: s.value(r, "corner_impact_force [N]") / 1e6),
    ("top_acceleration", "top-floor acceleration [m/s²]",
     lambda s, r: s.value(r, "top_acceleration [m/s^2]")),
    ("corner_drift", "peak corner drift [mm]", lambda s, r: 1000 * s.value(r, "corner_drift [m]")),
    ("rotation", "peak rotation [mrad]", lambda s, r: 1000 * s.value(r, "rotation [rad]")),
    ("n_impacts", "number of impacts", lambda s, r: s.value(r, "n_impacts")),
]


def chart_directionality(sweep, written, lines):
    """Peaks against the angle of incidence (the parameter that sets plan.angle), one line per
    value of the other swept parameters (e.g. the eccentricity); the largest of each peak and its
    case in the summary."""
    angle = next((p["name"] for p in sweep.params
                  if any("plan.angle" in s for s in p.get("settings", []))), None)
    if angle is None:
        raise ValueError("report kind directionality: no parameter sets plan.angle")
    series = [n for n in sweep.names if n != angle]
    panels_vs(sweep, sweep.ok, lambda r: number(r[angle]), "angle of incidence [deg from x]",
              series, PLAN_RESPONSES, "directionality", f"{sweep.title}: peaks against the angle",
              written)
    for key, label, fun in PLAN_RESPONSES[:-1]:
        vals = [(fun(sweep, r), r) for r in sweep.ok if math.isfinite(fun(sweep, r))]
        if vals:
            best = max(vals, key=lambda t: t[0])
            unit = re.search(r"\[(.*)\]", label).group(1)
            text = re.sub(r"\s*\[.*\]", "", label)
            lines.append(f"- largest {text}: {fmt(best[0])} {unit} at {describe(sweep, best[1])}")


def chart_gap_study(sweep, written, lines):
    gap_charts(sweep, sweep.ok, other_params(sweep), written)
    add_dreq_lines(sweep, lines)


def chart_wall_location(sweep, written, lines):
    chart_gap_study(sweep, written, lines)


def chart_flexibility(sweep, written, lines):
    companion = next((c["name"] for c in sweep.plan.get("companions", [])), None)

    def ratio(r):
        other = sweep.companion_of.get((companion, tuple(r[n] for n in sweep.names)))
        t_iso = sweep.value(r, f"{MAIN_BUILDING}.T1 [s]")
        t_fixed = sweep.value(other, f"{MAIN_BUILDING}.T1 [s]") if other else NAN
        return t_iso / t_fixed if t_fixed > 0 else NAN

    series = ([sweep.record_param] if sweep.record_param else []) + \
        [n for n in other_params(sweep) if "isolator" not in n] + (
        [sweep.gap_param] if sweep.gap_param else [])
    panels_vs(sweep, sweep.ok, ratio, "period ratio T_iso / T_fixed (isolated / fixed base)", series, AMPLIFICATIONS + RESPONSES[2:],
              "vs_period_ratio", f"{sweep.title}: response vs isolation flexibility", written)
    ratios = [(ratio(r), r) for r in sweep.ok if math.isfinite(ratio(r))]
    if ratios:
        lo, hi = min(ratios, key=lambda t: t[0]), max(ratios, key=lambda t: t[0])
        lines.append(f"- T_iso/T_fixed from {fmt(lo[0])} ({describe(sweep, lo[1])}) to {fmt(hi[0])} "
                     f"({describe(sweep, hi[1])}).")


def chart_impact_parameters(sweep, written, lines):
    names = [n for n in sweep.names if n != sweep.record_param and n != sweep.gap_param
             and len(sweep.params[sweep.names.index(n)]["values"]) > 1]
    if len(names) < 2:
        property_charts(sweep, written)
        return
    xa, ya = names[0], names[1]
    xs = sorted({quantity(r[xa])[0] for r in sweep.ok})
    ys = sorted({quantity(r[ya])[0] for r in sweep.ok})
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    for ax, (key, label, fun) in zip(axes.flat, [AMPLIFICATIONS[0], AMPLIFICATIONS[2], RESPONSES[3],
                                                 PEAK_FORCE]):
        grid = np.full((len(ys), len(xs)), np.nan)
        for r in sweep.ok:
            i, j = ys.index(quantity(r[ya])[0]), xs.index(quantity(r[xa])[0])
            v = fun(sweep, r)
            grid[i, j] = v if not np.isfinite(grid[i, j]) else max(grid[i, j], v)
        finite = grid[np.isfinite(grid)]
        if key == "n_impacts" and finite.size:
            # A count is discrete: one flat colour per case and integer steps on the colour bar,
            # not a smooth contour that invents fractional impacts between the cases.
            lo, hi = int(finite.min()), int(finite.max())
            step = max(1, math.ceil((hi - lo + 1) / 12))
            bounds = np.arange(lo - 0.5, hi + step + 0.5, step)
            cmap = plt.get_cmap("viridis", len(bounds) - 1)
            norm = matplotlib.colors.BoundaryNorm(bounds, cmap.N)
            mesh = ax.pcolormesh(xs, ys, grid, shading="nearest", cmap=cmap, norm=norm) \
                if len(xs) > 1 and len(ys) > 1 else ax.pcolormesh(grid, cmap=cmap, norm=norm)
            fig.colorbar(mesh, ax=ax, ticks=np.arange(lo, hi + step, step))
        else:
            mesh = ax.contourf(xs, ys, grid, levels=12, cmap="viridis") \
                if len(xs) > 1 and len(ys) > 1 else ax.pcolormesh(grid)
            fig.colorbar(mesh, ax=ax)
        ax.set_xlabel(axis_name(xa, quantity(sweep.ok[0][xa])[1]))
        ax.set_ylabel(axis_name(ya, quantity(sweep.ok[0][ya])[1]))
        ax.set_title(label, fontsize="medium")
    fig.suptitle(f"{sweep.title}: amplification surfaces (max over records)" if sweep.record_param
                 else f"{sweep.title}: amplification surfaces")
    fig.tight_layout()
    save(fig, sweep.dir, "amplification_surfaces", written)
    for key, label, fun in AMPLIFICATIONS[:1]:
        vals = [(fun(sweep, r), r) for r in sweep.ok if math.isfinite(fun(sweep, r))]
        if vals:
            lo = min(vals, key=lambda t: t[0])
            lines.append(f"- smallest {label}: {fmt(lo[0])} at {describe(sweep, lo[1])}.")


def chart_adjacent(sweep, written, lines):
    side = next((n for n in other_params(sweep)), None)
    rest = [n for n in other_params(sweep) if n != side]
    values = sweep.params[sweep.names.index(side)]["values"] if side else [None]
    for v in values:
        rows = [r for r in sweep.ok if side is None or r[side] == v]
        suffix = "" if v is None else "_" + re.sub(r"[^A-Za-z0-9]+", "_", v).strip("_")
        gap_charts(sweep, rows, rest, written, suffix, "" if v is None else f" ({side} = {v})")
    dsrss_chart_and_table(sweep, written, lines)


def chart_bumpers(sweep, written, lines):
    gap_values = sweep.params[sweep.names.index(sweep.gap_param)]["values"] if sweep.gap_param else []
    if len(gap_values) >= 3:
        gap_charts(sweep, sweep.ok, other_params(sweep), written)
        first = next(iter(other_params(sweep)), None)
        if first:
            for key, label, fun in AMPLIFICATIONS[:1] + RESPONSES[2:3]:
                for v in sweep.params[sweep.names.index(first)]["values"]:
                    vals = [fun(sweep, r) for r in sweep.ok if r[first] == v]
                    vals = [x for x in vals if math.isfinite(x)]
                    if vals:
                        lines.append(f"- {first} = {v}: mean {label} {fmt(float(np.mean(vals)))}, "
                                     f"max {fmt(max(vals))} ({len(vals)} cases).")
    else:
        property_charts(sweep, written)


# ------------------------------------------------------------------------------- d_req / d_SRSS
def add_dreq_lines(sweep, lines):
    path = os.path.join(sweep.dir, "dsrss_table.csv")
    if not os.path.exists(path):
        return
    table = sweep.read_table(path)
    if not table:
        return
    params = [n for n in sweep.names if n in table[0]]
    reached = [r for r in table if r["d_req_status"] in ("reached", "at_smallest_gap")]
    n_not = sum(r["d_req_status"] == "not_reached" for r in table)
    if reached:
        worst = max(reached, key=lambda r: number(r["d_req [m]"]))
        lines.append(f"- largest gap found necessary to avoid pounding (d_req): "
                     f"{fmt(number(worst['d_req [m]']) * 100)} cm for "
                     f"{', '.join(f'{p} = {worst[p]}' for p in params) or 'the only configuration'}.")
    lines.append(f"- {n_not} of {len(table)} configurations still pound at the largest swept gap "
                 f"(d_req not reached; see the table below).")


def dsrss_chart_and_table(sweep, written, lines):
    path = os.path.join(sweep.dir, "dsrss_table.csv")
    if not os.path.exists(path):
        lines.append("- no `dsrss_table.csv` (the sweep has no SRSS metrics).")
        return
    table = sweep.read_table(path)
    params = [n for n in sweep.names if n in table[0]] if table else []
    deltas = [(number(r["delta_d [m]"]), r) for r in table if math.isfinite(number(r["delta_d [m]"]))]
    n_not = sum(r["d_req_status"] == "not_reached" for r in table)
    if deltas:
        lo, hi = min(deltas, key=lambda t: t[0]), max(deltas, key=lambda t: t[0])
        name = lambda r: ", ".join([f"{p} = {r[p]}" for p in params]  # noqa: E731
                                   + [f"clearance − gap {fmt(number(r['clearance_offset [m]']) * 100)} cm"])
        lines.append(f"- Δd = d_SRSS − d_req from {fmt(lo[0] * 100)} cm ({name(lo[1])}) to "
                     f"{fmt(hi[0] * 100)} cm ({name(hi[1])}); negative Δd: SRSS gap too small; "
                     f"{sum(d < 0 for d, _ in deltas)} of {len(deltas)} configurations with a "
                     f"found d_req are unconservative; {n_not} never stop pounding in the swept range.")
    # Chart: d_SRSS and d_req per configuration (one point per table row, grouped by record).
    record = sweep.record_param if sweep.record_param in params else None
    groups = {}
    for r in table:
        groups.setdefault(r[record] if record else "all", []).append(r)
    fig, axes = plt.subplots(len(groups), 1, figsize=(max(10, 0.12 * len(table)), 3.8 * len(groups)),
                             squeeze=False)
    for ax, (g, rows) in zip(axes[:, 0], groups.items()):
        x = np.arange(len(rows))
        d_req = [number(r["d_req [m]"]) * 100 for r in rows]
        d_srss = [number(r["d_srss [m]"]) * 100 for r in rows]
        not_reached = [i for i, r in enumerate(rows) if r["d_req_status"] == "not_reached"]
        ax.plot(x, d_srss, "s", label="d_SRSS")
        ax.plot(x, d_req, "o", label="d_req (sweep)")
        if not_reached:
            ax.plot(not_reached, [number(rows[i]["gap_max [m]"]) * 100 for i in not_reached], "^",
                    color="red", label="d_req > largest gap")
        ax.set_xticks(x)
        ax.set_xticklabels([", ".join(r[p] for p in params if p != record)
                            + (f" {number(r['clearance_offset [m]']) * 100:+g} cm"
                               if number(r["clearance_offset [m]"]) else "") for r in rows],
                           rotation=90, fontsize=6)
        ax.set_ylabel("gap [cm]")
        ax.set_title(f"{record} = {g}" if record else "", fontsize="medium")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="small")
    fig.suptitle(f"{sweep.title}: required gap found by the sweep vs SRSS")
    fig.tight_layout()
    save(fig, sweep.dir, "dsrss", written)


def dsrss_markdown(sweep):
    path = os.path.join(sweep.dir, "dsrss_table.csv")
    if not os.path.exists(path):
        return []
    table = sweep.read_table(path)
    if not table:
        return []
    params = [n for n in sweep.names if n in table[0]]
    out = ["", "## Required gap: sweep (d_req) against SRSS (d_SRSS)", "",
           "d_SRSS = max over contacts of (sqrt(d_L² + d_R²) − (clearance − gap)) from the run "
           "without contacts; d_req = smallest swept gap from which on no contact has an impact; "
           "Δd = d_SRSS − d_req (from `dsrss_table.csv`).", "",
           "| " + " | ".join(params) + " | clearance − gap [cm] | d_req [cm] | d_SRSS [cm] | Δd [cm] | governing |",
           "|" + "---|" * (len(params) + 5)]
    for r in table:
        d_req = number(r["d_req [m]"]) * 100
        status = r["d_req_status"]
        d_req_text = {"not_reached": f"> {fmt(number(r['gap_max [m]']) * 100)}",
                      "at_smallest_gap": f"≤ {fmt(d_req)}", "no_data": "n/a"}.get(status, fmt(d_req))
        out.append("| " + " | ".join(r[p] for p in params)
                   + f" | {fmt(number(r['clearance_offset [m]']) * 100)} | {d_req_text} | "
                   f"{fmt(number(r['d_srss [m]']) * 100)} | {fmt(number(r['delta_d [m]']) * 100)} | "
                   f"{r['governing_contact']} |")
    return out


# ---------------------------------------------------------------------------------------- summary
def key_numbers(sweep):
    lines = []
    for key, label, fun in AMPLIFICATIONS + RESPONSES + [PEAK_FORCE]:
        vals = [(fun(sweep, r), r) for r in sweep.ok if math.isfinite(fun(sweep, r))]
        if not vals:
            continue
        best = max(vals, key=lambda t: t[0])
        unit = re.search(r"\[(.*)\]", label)
        text = re.sub(r"\s*\[.*\]", "", label)
        lines.append(f"- largest {text}: {fmt(best[0])}{' ' + unit.group(1) if unit else ''} "
                     f"at {describe(sweep, best[1])}")
    return lines


def write_summary(sweep, written, extra):
    n_comp = len(sweep.rows) - len(sweep.main)
    swept = []
    for p in sweep.params:
        vals = [shown(v) for v in p["values"]]
        listed = ", ".join(vals) if len(vals) <= 6 else f"{vals[0]}, {vals[1]}, …, {vals[-1]}"
        swept.append(f"- `{p['name']}`: {len(vals)} values ({listed})")
    failures = {}
    for r in sweep.failed:
        failures[r["status"]] = failures.get(r["status"], 0) + 1
    text = [f"# {sweep.title}", "",
            f"Sweep file `{sweep.plan.get('file', '')}`, base scene `{sweep.plan.get('scene', '')}`, "
            f"report kind `{sweep.kind}`.", "",
            "## What was swept", "",
            f"{len(sweep.main)} cases ({len(sweep.ok)} ok, {len(sweep.failed)} failed)"
            + (f" and {n_comp} companion runs ({', '.join(c['name'] for c in sweep.plan.get('companions', []))})"
               if n_comp else "") + f"; combination: {sweep.plan.get('combine', 'product')}.", ""]
    text += swept
    if failures:
        text += ["", "Failures:"] + [f"- {n} × {s}" for s, n in sorted(failures.items())]
    text += ["", "## Key numbers", "",
             "Maxima over all successful cases. Floor accelerations: the main building's floors above "
             "the isolation level; drifts: its storeys; base: the isolation level; amplification = "
             "peak with pounding / peak of the run without contacts.", ""]
    text += key_numbers(sweep) + extra
    text += dsrss_markdown(sweep)
    text += ["", "## Charts", ""]
    text += [f"- [{name}](charts/{name}.svg) ![{name}](charts/{name}.png)" for name in written]
    final = os.path.join(sweep.dir, "summary.md")
    temp = final + f".tmp-{os.getpid()}"
    with open(temp, "w") as f:
        f.write("\n".join(text) + "\n")
    os.replace(temp, final)


KINDS = {
    "gap_study": chart_gap_study,
    "isolation_flexibility": chart_flexibility,
    "wall_location": chart_wall_location,
    "impact_parameters": chart_impact_parameters,
    "adjacent_buildings": chart_adjacent,
    "bumpers": chart_bumpers,
    "directionality": chart_directionality,
}


def main(argv):
    if len(argv) != 2:
        print(f"usage: {argv[0]} SWEEP_OUTPUT_DIR", file=sys.stderr)
        return 2
    sweep = Sweep(argv[1])
    if sweep.kind not in KINDS:
        print(f"report.kind = {sweep.kind} (expected one of {', '.join(KINDS)})", file=sys.stderr)
        return 2
    written, extra = [], []
    status = 0
    if sweep.ok:
        try:
            KINDS[sweep.kind](sweep, written, extra)
        except Exception:  # the summary is still written, then the failure is reported
            traceback.print_exc()
            extra.append(f"- **chart failure** ({sweep.kind}): see charts/charts.log; charts "
                         f"written before it are listed below.")
            status = 1
    write_summary(sweep, written, extra)
    print(f"{len(written)} charts and summary.md written to {sweep.dir}")
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
