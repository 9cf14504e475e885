"""Chart building blocks of scripts/sweep_charts.py: the responses drawn, saving a figure as PNG
and SVG under a temporary name, panels of a response against a parameter (mean and spread over the
other parameters), the gap charts with the required gap d_req, and property charts."""
import math
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

from sweep_data import RECORD_KEY, axis_name, fmt, length_m, number, quantity

# Responses charted for every kind: (key, label, function(sweep, row)).
RESPONSES = [
    ("floor_acc", "max floor acceleration [m/s²]",
     lambda s, r: s.floors_max(r, "peak_abs_acceleration_dof{} [m/s^2]")),
    ("drift", "max interstorey drift [cm]",
     lambda s, r: 100 * s.storeys_max(r, "peak_drift_storey{} [m]")),
    ("impact_velocity", "max impact velocity [m/s]", lambda s, r: s.impact_velocity(r)),
    ("n_impacts", "number of impacts", lambda s, r: s.value(r, "n_impacts")),
]
PEAK_FORCE = ("peak_force", "peak impact force [MN]",
              lambda s, r: s.contacts_max(r, ".peak_force [N]") / 1e6)
AMPLIFICATIONS = [
    ("amp_floor_acc", "amplification of the floor acceleration",
     lambda s, r: s.floors_max(r, "amp_abs_acceleration_dof{}")),
    ("amp_base_acc", "amplification of the base acceleration",
     lambda s, r: s.value(r, f"amp_abs_acceleration_dof{s.block(r)[0]}")),
    ("amp_drift", "amplification of the interstorey drift",
     lambda s, r: s.storeys_max(r, "amp_drift_storey{}")),
]


# ---------------------------------------------------------------------------------------- output
def save(fig, directory, name, written):
    os.makedirs(os.path.join(directory, "charts"), exist_ok=True)
    for ext in ("png", "svg"):
        final = os.path.join(directory, "charts", f"{name}.{ext}")
        temp = final + f".tmp-{os.getpid()}"
        fig.savefig(temp, format=ext, dpi=110, bbox_inches="tight")
        os.replace(temp, final)
    plt.close(fig)
    written.append(name)


def shown(value):
    return "none" if value in ("~", "null") else value


def describe(sweep, row, skip=()):
    """The varied parameters of a row (single-valued ones are the same for every row)."""
    parts = []
    for p in sweep.params:
        n = p["name"]
        if n in skip or len(p["values"]) < 2:
            continue
        if n == sweep.gap_param:
            parts.append(f"gap {fmt(sweep.gap(row) * 100)} cm")
            off = sweep.separation_offset(row)
            if off:
                parts.append(off)
        else:
            parts.append(f"{n} = {shown(row[n])}")
    return ", ".join(parts) or "the only case"


def series_label(sweep, row, params):
    parts = [value_words(sweep, n, row[n]) for n in params]
    if sweep.gap_param and sweep.gap_param not in params:
        off = sweep.separation_offset(row)
        if off and sweep.kind == "adjacent_buildings":
            parts.append(off)
    return ", ".join(parts) or "all"


def stats_vs(sweep, rows, xfun, yfun, series_params):
    """{(series label, its parameter values): (x, max over the rest, mean over the rest, largest
    number of rows at one x)} with finite values only."""
    data = {}
    for r in rows:
        x, y = xfun(r), yfun(sweep, r)
        if not (math.isfinite(x) and math.isfinite(y)):
            continue
        key = (series_label(sweep, r, series_params), tuple(r[n] for n in series_params))
        data.setdefault(key, {}).setdefault(round(x, 9), []).append(y)
    out = {}
    for key, by_x in data.items():
        xs = sorted(by_x)
        out[key] = (np.array(xs), np.array([max(by_x[x]) for x in xs]),
                    np.array([float(np.mean(by_x[x])) for x in xs]),
                    max(len(v) for v in by_x.values()))
    return out


def panels_vs(sweep, rows, xfun, xlabel, series_params, responses, name, title, written,
              xticks=None):
    """One panel per response against x; one line per series (with two series parameters:
    colour for the first, line style for the second); rows of one series at one x give its max
    (solid) and, with a single series parameter or none, its mean (dashed)."""
    n = len(responses)
    cols = 2
    fig, axes = plt.subplots((n + 1) // cols, cols, figsize=(12, 4.2 * ((n + 1) // cols)),
                             squeeze=False)
    values = {p: sweep.params[sweep.names.index(p)]["values"] for p in series_params}
    styled = len(series_params) == 2 and len(values[series_params[1]]) <= len(LINE_STYLES)
    over = "records" if sweep.record_param and sweep.record_param not in series_params \
        else "the parameters not in the legend"
    aggregated = False
    for ax, (key_name, label, fun) in zip(axes.flat, responses):
        if key_name == "n_impacts":  # a count: integer ticks
            ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
        data = stats_vs(sweep, rows, xfun, fun, series_params)
        aggregated = aggregated or any(d[3] > 1 for d in data.values())
        order = sorted(data, key=lambda k: tuple(values[p].index(v)
                                                 for p, v in zip(series_params, k[1])))
        for i, key in enumerate(order):
            x, ymax, ymean, n_per_x = data[key]
            s = key[0]
            if styled:
                color = f"C{values[series_params[0]].index(key[1][0]) % 10}"
                style = LINE_STYLES[values[series_params[1]].index(key[1][1])]
            else:
                color, style = f"C{i % 10}", "-"
            # A count (number of impacts): a hollow marker of the line's own shape on every
            # swept value, so that lines with equal counts stay visible on top of each other.
            count = key_name == "n_impacts"
            marker = COUNT_MARKERS[i % len(COUNT_MARKERS)] if count else \
                "o" if len(x) < 4 else None
            look = dict(ms=6, mfc="none", mew=1.3, lw=0.9) if count else {}
            gid = "series-" + slug("_".join(key[1]))
            ax.plot(x, ymax, style, color=color, marker=marker, gid=gid,
                    label=f"{s} (max)" if n_per_x > 1 else s, **look)
            if n_per_x > 1 and not styled:
                ax.plot(x, ymean, "--", color=color, marker=marker, label=f"{s} (mean)", **look)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        if xticks:
            ax.set_xticks(range(len(xticks)))
            ax.set_xticklabels(xticks)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    handles, labels = axes.flat[0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0),
                   ncol=min(3, len(labels)), fontsize="small")
    if aggregated and styled:
        title += f"\n(max over {over})"
    elif aggregated:
        title += f"\n(solid: max, dashed: mean over {over})"
    fig.suptitle(title)
    fig.tight_layout()
    save(fig, sweep.dir, name, written)


def other_params(sweep, *exclude):
    return [n for n in sweep.names
            if n not in exclude and n != sweep.gap_param and n != sweep.record_param
            and len(sweep.params[sweep.names.index(n)]["values"]) > 1]


# Gap charts: one column of panels per record, one line per record and configuration (the other
# varied parameters: colour for the first, line style for the second), the required gap d_req of
# dsrss_table.csv marked on each line.
LINE_STYLES = ["-", "--", ":", "-."]
COUNT_MARKERS = ["o", "s", "^", "D", "v", "P", "X"]
DREQ_MARK = {"reached": ("D", "d_req: smallest swept gap without impact"),
             "at_smallest_gap": ("<", "d_req ≤ smallest swept gap (no impact at any gap)"),
             "not_reached": (">", "d_req > largest swept gap (impacts at every gap)")}


def slug(text):
    return re.sub(r"[^A-Za-z0-9]+", "_", str(text)).strip("_") or "all"


def value_words(sweep, name, value):
    """A parameter value in words: "4 storeys", "unscaled", "PGA 1 g", "COR 0.5"."""
    value = shown(value)
    if name == "building.n_storeys":
        return f"{value} storeys"
    if name.startswith("neighbours.") and name.endswith("n_storeys"):
        return f"{value}-storey neighbour"
    if name == "ground_motion.scale_to_pga":
        return "unscaled" if value == "none" else f"scaled to PGA {value}"
    if name == sweep.record_param:
        return record_words(sweep, value)
    if not math.isfinite(quantity(value)[0]):  # a word or a label: "bumpers: with"
        return f"{axis_name(name)}: {value.replace('_', ' ')}"
    return f"{axis_name(name)} {value}"


def record_words(sweep, label):
    """A record value: its label and, when the label is not the record's name, the name."""
    if not sweep.record_param:
        return label
    p = sweep.params[sweep.names.index(sweep.record_param)]
    setting = p["settings"][p["values"].index(label)] if label in p["values"] else {}
    name = str(setting.get(RECORD_KEY, label)).strip('"')
    name = os.path.basename(name)
    return label if name in (label, "") else f"{label} ({name})"


class RequiredGaps:
    """d_req of dsrss_table.csv by configuration (the values of its parameter columns)."""

    def __init__(self, sweep):
        self.params, self.rows = [], {}
        path = os.path.join(sweep.dir, "dsrss_table.csv")
        if not os.path.exists(path):
            return
        table = sweep.read_table(path)
        self.params = [n for n in sweep.names if n in table[0]] if table else []
        for r in table:
            self.rows.setdefault(tuple(r[p] for p in self.params), []).append(r)

    def of(self, sweep, row):
        """(d_req in cm or nan, status) of the configuration of `row`, or None."""
        candidates = self.rows.get(tuple(row.get(p) for p in self.params), [])
        if len(candidates) > 1:  # several clearances (e.g. a neighbour's separation): row's own
            offsets = {0.0}
            if sweep.gap_param:
                p = sweep.params[sweep.names.index(sweep.gap_param)]
                settings = p["settings"][p["values"].index(row[sweep.gap_param])]
                offsets |= {round(length_m(t) - sweep.gap(row), 6) for t in settings.values()
                            if math.isfinite(length_m(t))}
            candidates = [c for c in candidates
                          if round(number(c["clearance_offset [m]"]), 6) in offsets][-1:]
        if len(candidates) != 1:
            return None
        c = candidates[0]
        return number(c["d_req [m]"]) * 100, c["d_req_status"]


def gap_charts(sweep, rows, series, written, suffix="", title_extra=""):
    gap_panels(sweep, rows, series, RESPONSES, "response_vs_gap" + suffix,
               f"{sweep.title}{title_extra}: response vs gap", written)
    if any(c.startswith("amp_") for c in sweep.columns):
        gap_panels(sweep, rows, series, AMPLIFICATIONS, "amplification_vs_gap" + suffix,
                   f"{sweep.title}{title_extra}: amplification vs gap", written)


def gap_panels(sweep, rows, series, responses, name, title, written):
    """Rows: responses; columns: records (one column without a record parameter); in each panel
    one line per configuration of `series`, with its d_req marked."""
    required = RequiredGaps(sweep)
    records = [v for v in sweep.params[sweep.names.index(sweep.record_param)]["values"]
               if any(r[sweep.record_param] == v for r in rows)] if sweep.record_param else [None]
    values = {n: [v for v in sweep.params[sweep.names.index(n)]["values"]
                  if any(r[n] == v for r in rows)] for n in series}
    colour_param = series[0] if series else None
    style_param = series[1] if len(series) == 2 and len(values[series[1]]) <= len(LINE_STYLES) \
        else None
    combos = sorted({tuple(r[n] for n in series) for r in rows},
                    key=lambda c: tuple(values[n].index(v) for n, v in zip(series, c)))
    offsets = sorted({sweep.separation_offset(r) for r in rows},
                     key=lambda o: [float(v) for v in re.findall(r"[-+][0-9.]+", o)]) \
        if sweep.kind == "adjacent_buildings" else [""]
    # One parameter and several separations: colour for the parameter, style for the separation.
    by_offset = not style_param and len(series) == 1 and 1 < len(offsets) <= len(LINE_STYLES)
    lines_per_panel = [(c, o) for c in combos for o in offsets]

    def look(combo, offset_index):
        i = lines_per_panel.index((combo, offsets[offset_index]))
        if style_param:
            colour = values[colour_param].index(combo[0])
            style = LINE_STYLES[values[style_param].index(combo[1])]
        elif by_offset:
            colour = values[colour_param].index(combo[0])
            style = LINE_STYLES[offset_index]
        else:
            colour, style = i, LINE_STYLES[offset_index % len(LINE_STYLES)]
        return f"C{colour % 10}", style

    n_rows, n_cols = len(responses), len(records)
    fig, axes = plt.subplots(n_rows, n_cols, figsize=(4.6 * n_cols + 1.5, 2.9 * n_rows + 1.2),
                             squeeze=False, sharex=True, sharey="row")
    aggregated = False
    marks_used = set()
    gap_words = axis_name(sweep.gap_key, "cm")
    for j, record in enumerate(records):
        record_rows = [r for r in rows if record is None or r[sweep.record_param] == record]
        for i, (key_name, label, fun) in enumerate(responses):
            ax = axes[i, j]
            if key_name == "n_impacts":  # a count: integer ticks
                ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
            n_drawn = {}
            for combo in combos:
                for k, offset in enumerate(offsets):
                    chosen = [r for r in record_rows if tuple(r[n] for n in series) == combo
                              and (not offset or sweep.separation_offset(r) == offset)]
                    by_x = {}
                    for r in chosen:
                        x, y = sweep.gap(r) * 100, fun(sweep, r)
                        if math.isfinite(x) and math.isfinite(y):
                            by_x.setdefault(round(x, 9), []).append(y)
                    if not by_x:
                        continue
                    aggregated = aggregated or any(len(v) > 1 for v in by_x.values())
                    xs = np.array(sorted(by_x))
                    ys = np.array([max(by_x[x]) for x in xs])
                    colour, style = look(combo, k)
                    key = "--".join([slug(record), slug("_".join(list(combo) + [offset])),
                                     key_name])
                    if key_name == "n_impacts":
                        # A count: a hollow marker of its own shape on every swept gap, so that
                        # lines with equal counts stay visible on top of each other.
                        shape = COUNT_MARKERS[len(ax.get_lines()) % len(COUNT_MARKERS)]
                        ax.plot(xs, ys, style, color=colour, lw=0.9, marker=shape, ms=6,
                                mfc="none", mew=1.3, gid=f"series-{key}")
                    else:
                        ax.plot(xs, ys, style, color=colour, lw=1.4,
                                marker="o" if len(xs) < 4 else None, ms=3, gid=f"series-{key}")
                    dreq = required.of(sweep, chosen[0])
                    if dreq is None or dreq[1] not in DREQ_MARK:
                        continue
                    at, status = dreq
                    x_mark = {"not_reached": xs[-1], "at_smallest_gap": xs[0]}.get(status, at)
                    marker, _ = DREQ_MARK[status]
                    marks_used.add(status)
                    # A mark on top of an earlier one is drawn smaller: equal d_req nest.
                    y_mark = float(np.interp(x_mark, xs, ys))
                    spot = (round(x_mark, 6), round(y_mark, 6))
                    size = max(3.0, 8.0 - 2.0 * n_drawn.get(spot, 0))
                    n_drawn[spot] = n_drawn.get(spot, 0) + 1
                    ax.plot([x_mark], [y_mark], marker, ms=size,
                            mfc=colour, mec="black", mew=0.9, color=colour, zorder=5,
                            gid=f"d_req-{key}")
            ax.grid(True, alpha=0.3)
            if j == 0:
                ax.set_ylabel(label)
            if i == n_rows - 1:
                ax.set_xlabel(gap_words)
            if i == 0 and record is not None:
                ax.set_title(f"record: {record_words(sweep, record)}", fontsize="medium")
    # Legend: one column per group (colour, line style, d_req marks), or the lines' names.
    from matplotlib.lines import Line2D
    groups = []
    if style_param:
        groups.append([Line2D([], [], color=f"C{i % 10}", lw=2,
                              label=value_words(sweep, colour_param, v))
                       for i, v in enumerate(values[colour_param])])
        groups.append([Line2D([], [], color="0.3", ls=LINE_STYLES[i], lw=1.4,
                              label=value_words(sweep, style_param, v))
                       for i, v in enumerate(values[style_param])])
    elif by_offset:
        groups.append([Line2D([], [], color=f"C{i % 10}", lw=2,
                              label=value_words(sweep, colour_param, v))
                       for i, v in enumerate(values[colour_param])])
        groups.append([Line2D([], [], color="0.3", ls=LINE_STYLES[k], lw=1.4, label=o)
                       for k, o in enumerate(offsets)])
    else:
        named = []
        for combo in combos:
            for k, offset in enumerate(offsets):
                colour, style = look(combo, k)
                words = [value_words(sweep, n, v) for n, v in zip(series, combo)] + \
                    ([offset] if offset else [])
                named.append(Line2D([], [], color=colour, ls=style, lw=1.4,
                                    label=", ".join(words) or "response"))
        per_column = max(1, math.ceil(len(named) / 3))
        groups += [named[i:i + per_column] for i in range(0, len(named), per_column)]
    marks = [Line2D([], [], ls="", marker=DREQ_MARK[s][0], ms=7, mfc="white", mec="black",
                    label=DREQ_MARK[s][1])
             for s in ("reached", "at_smallest_gap", "not_reached") if s in marks_used]
    if marks:
        groups.append(marks)
    height = max((len(g) for g in groups), default=0)
    handles = []
    for g in groups:  # the legend fills column by column: pad each group to the same height
        handles += g + [Line2D([], [], ls="", label=" ")] * (height - len(g))
    if handles:
        fig.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, 0.0),
                   ncol=len(groups), fontsize="small", frameon=False)
    note = " (max over the parameters not in the legend)" if aggregated else ""
    fig.suptitle(title + note)
    fig.tight_layout(rect=(0, min(0.3, (0.17 * height + 0.15) / fig.get_figheight()), 1, 1))
    save(fig, sweep.dir, name, written)


def property_charts(sweep, written):
    for name in other_params(sweep):
        p = sweep.params[sweep.names.index(name)]
        numeric = [quantity(v)[0] for v in p["values"]]
        ticks = None
        if all(math.isfinite(v) for v in numeric):
            x = lambda r, n=name: quantity(r[n])[0]  # noqa: E731
            unit = quantity(p["values"][0])[1]
            xlabel = axis_name(name, unit)
        else:  # words (a law, yes/no): one tick per value, named
            x = lambda r, n=name, vals=p["values"]: float(vals.index(r[n]))  # noqa: E731
            xlabel = axis_name(name)
            ticks = [shown(v) for v in p["values"]]
        responses = [a for a in AMPLIFICATIONS if a[0] != "amp_base_acc"] + RESPONSES[2:]
        panels_vs(sweep, sweep.ok, x, xlabel, [sweep.record_param] if sweep.record_param else [],
                  responses,
                  "vs_" + re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_"),
                  f"{sweep.title}: response vs {axis_name(name)}", written, ticks)
