#!/usr/bin/python3
"""Charts and summary.md of `kimp sweep SWEEP.yaml -o DIR` (studies 1-6 of data/studies).
Reads DIR/sweep.csv, the plan JSON in DIR/sweep.h5 (/input/resolved: parameters, their settings and
the `report:` section) and DIR/dsrss_table.csv if present; writes DIR/charts/*.png and *.svg and
DIR/summary.md, each under a temporary name renamed when complete. Every number comes from the data."""
import csv
import json
import math
import os
import re
import sys
import traceback

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

LENGTH_UNITS = {"mm": 1e-3, "cm": 1e-2, "m": 1.0}
RECORD_KEY = "ground_motion.record"
MAIN_BUILDING = "building"
NAN = float("nan")


# ---------------------------------------------------------------------------------------- input
def read_plan(directory):
    with h5py.File(os.path.join(directory, "sweep.h5"), "r") as f:
        node = f["input/resolved"]
        text = node[()] if isinstance(node, h5py.Dataset) else node.attrs["text"]
    if isinstance(text, bytes):
        text = text.decode()
    if isinstance(text, np.ndarray):
        text = text.item().decode() if isinstance(text.item(), bytes) else str(text.item())
    return json.loads(text)


def csv_column(label):
    """The CSV column of a metric label "name [unit]" (kimp's header convention name_unit,
    io::csv_column): '/' -> "_per_", '^' and spaces dropped, '*' -> '_', no suffix for "1"."""
    if not label.endswith("]") or " [" not in label:
        return label
    name, unit = label[:-1].rsplit(" [", 1)
    if unit in ("", "1"):
        return name
    unit = unit.replace("/", "_per_").replace("^", "").replace(" ", "").replace("*", "_")
    return f"{name}_{unit}"


class Row(dict):
    """A CSV row that also answers to the metric labels "name [unit]" of sweep.h5."""

    def __missing__(self, key):
        column = csv_column(key)
        if column != key and column in self:
            return self[column]
        raise KeyError(key)

    def get(self, key, default=None):
        try:
            return self[key]
        except KeyError:
            return default


def read_csv(path):
    with open(path, newline="") as f:
        return [Row(r) for r in csv.DictReader(f)]


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return NAN


# Axis names of common scene key paths (the key path itself is a file detail, not a quantity).
KEY_NAMES = {
    "impact.k": "impact stiffness k",
    "impact.cor": "coefficient of restitution",
    "impact.law": "impact law",
    "walls.left.gap": "gap to the moat wall",
    "walls.right.gap": "gap to the moat wall",
    "ground_motion.record": "record",
    "ground_motion.scale": "record scale",
    "ground_motion.scale_to_pga": "record scaled to PGA",
    "building.n_storeys": "storeys",
    "isolator.k": "isolator stiffness",
    "isolator.kind": "isolator",
    "isolator.damping_ratio": "isolator damping ratio",
    "impact.bumper.thickness": "bumper thickness",
    "impact.bumper.ultimate_strain": "bumper ultimate strain",
    "impact.bumper.recessed": "bumper recessed",
    "impact.bumper.count": "number of bumpers",
    "impact.bumper.wall_stiffness": "wall stiffness behind the bumper",
    "neighbours.left.n_storeys": "neighbour storeys",
    "neighbours.right.n_storeys": "neighbour storeys",
    "neighbours.left.separation": "separation to the neighbour",
}


def axis_name(key, unit=""):
    """A readable axis label for a scene key path: a known name, else its last segment with spaces
    ("isolator.K1" -> "K1"); the several key paths of one parameter ("a, b") give the first one's
    name."""
    first = key.split(",")[0].strip()
    name = KEY_NAMES.get(first, first.split(".")[-1].replace("_", " "))
    return f"{name} [{unit}]" if unit else name


def quantity(text):
    """'10.5 cm' -> (10.5, 'cm'); '0.7' -> (0.7, ''); non-numbers -> (nan, text)."""
    match = re.match(r"^\s*([-+0-9.eE]+)\s*(.*?)\s*$", str(text))
    if not match:
        return NAN, str(text)
    try:
        return float(match.group(1)), match.group(2)
    except ValueError:
        return NAN, str(text)


def length_m(text):
    value, unit = quantity(text)
    return value * LENGTH_UNITS[unit] if unit in LENGTH_UNITS else NAN


def fmt(value, digits=4):
    return "n/a" if value is None or not math.isfinite(value) else f"{value:.{digits}g}"


class Sweep:
    """The rows of one sweep with the plan's parameters and derived per-row quantities."""

    def __init__(self, directory):
        self.dir = directory
        self.plan = read_plan(directory)
        self.report = self.plan.get("report") or {"kind": "gap_study", "gap": "walls.left.gap"}
        self.kind = self.report.get("kind", "gap_study")
        self.gap_key = self.report.get("gap") or "walls.left.gap"
        self.title = self.report.get("title") or os.path.basename(self.plan.get("file", directory))
        self.params = self.plan["parameters"]
        for p in self.params:  # plans written before settings were stored: scalar values only
            if not p.get("settings"):
                p["settings"] = [{k: v for k in p["key_paths"]} for v in p["values"]]
        self.names = [p["name"] for p in self.params]
        self.rows = read_csv(os.path.join(directory, "sweep.csv"))
        self.columns = list(self.rows[0].keys()) if self.rows else []
        self._read_parameter_values(directory)
        self.main = [r for r in self.rows if not r["companion"]]
        self.ok = [r for r in self.main if r["status"] == "ok"]
        self.failed = [r for r in self.main if r["status"] != "ok"]
        self.gap_param = next((p["name"] for p in self.params
                               if any(self.gap_key in s for s in p.get("settings", []))), None)
        self.record_param = next((p["name"] for p in self.params
                                  if any(RECORD_KEY in s for s in p.get("settings", []))), None)
        self.companion_of = {}
        for r in self.rows:
            if r["companion"]:
                self.companion_of[(r["companion"], tuple(r[n] for n in self.names))] = r

    def _read_parameter_values(self, directory):
        """sweep.csv holds each parameter as a number in one unit (or as text) under the column of
        /sweep/parameter_columns; the value texts of the sweep file ("4 cm"), row by row, are
        /sweep/parameters/<name>. Rows get them under the parameter's name, and the cells of each
        column map back to them (for dsrss_table.csv)."""
        self.cell_values = {}
        with h5py.File(os.path.join(directory, "sweep.h5"), "r") as f:
            if "sweep/parameter_columns" not in f:  # older sweeps: the texts are the columns
                return
            columns = [c.decode() if isinstance(c, bytes) else str(c)
                       for c in f["sweep/parameter_columns"][()]]
            for name, column in zip(self.names, columns):
                texts = f["sweep/parameters/" + name.replace("/", "_")][()]
                texts = [t.decode() if isinstance(t, bytes) else str(t) for t in texts]
                mapping = self.cell_values.setdefault(name, (column, {}))[1]
                for row, text in zip(self.rows, texts):
                    mapping[row[column]] = text
        self.with_values(self.rows)

    def with_values(self, rows):
        """Set row[parameter name] to the sweep file's value text from the parameter's column."""
        for row in rows:
            for name, (column, mapping) in self.cell_values.items():
                if column in row:
                    row[name] = mapping.get(row[column], row[column])
        return rows

    def read_table(self, path):
        """A CSV of the sweep directory (dsrss_table.csv) with the parameters' value texts."""
        return self.with_values(read_csv(path))

    def setting(self, row, name, key):
        p = self.params[self.names.index(name)]
        i = p["values"].index(row[name])
        return p["settings"][i].get(key) if p.get("settings") else row[name]

    def gap(self, row):
        """Swept gap of a row, m (nan when the gap is not varied)."""
        if "_gap" not in row:
            row["_gap"] = length_m(self.setting(row, self.gap_param, self.gap_key)) \
                if self.gap_param else NAN
        return row["_gap"]

    def separation_offset(self, row):
        """Lengths set together with the gap under other names (e.g. a neighbour's separation)
        minus the gap: 'separation +5 cm'."""
        if "_offset" not in row:
            row["_offset"] = self._separation_offset(row)
        return row["_offset"]

    def _separation_offset(self, row):
        if not self.gap_param:
            return ""
        p = self.params[self.names.index(self.gap_param)]
        settings = p["settings"][p["values"].index(row[self.gap_param])]
        gap = self.gap(row)
        last = self.gap_key.split(".")[-1]
        offsets = {}
        for key, text in settings.items():
            name = key.split(".")[-1]
            if name != last and math.isfinite(length_m(text)):
                offsets.setdefault(name, set()).add(round((length_m(text) - gap) * 100, 6))
        return ", ".join(f"{name} {o:+g} cm" for name, values in sorted(offsets.items())
                         for o in sorted(values))

    def value(self, row, column):
        return number(row.get(column))

    def block(self, row, name=MAIN_BUILDING):
        key = "_block_" + name
        if key not in row:
            row[key] = self._block(row, name)
        return row[key]

    def _block(self, row, name):
        first = self.value(row, f"{name}.first_dof")
        n = self.value(row, f"{name}.n_dofs")
        storeys = self.value(row, f"{name}.n_storeys")
        if not math.isfinite(first):  # sweeps written before these metrics: all DOFs
            dofs = [c for c in self.columns if c.startswith("peak_displacement_dof")]
            drifts = [c for c in self.columns if c.startswith("peak_drift_storey")]
            return 0, len(dofs), len(drifts)
        return int(first), int(n), int(storeys)

    def floors_max(self, row, pattern):
        """Max over the main building's floors above the isolation level (an isolated building
        has one DOF more than storeys: DOF 0 is the isolation level)."""
        first, n, storeys = self.block(row)
        start = max(0, n - storeys)
        values = [self.value(row, pattern.format(first + i)) for i in range(start, n)]
        values = [v for v in values if math.isfinite(v)]
        return max(values) if values else NAN

    def storeys_max(self, row, pattern):
        _, _, n = self.block(row)
        values = [self.value(row, pattern.format(s)) for s in range(n)]
        values = [v for v in values if math.isfinite(v)]
        return max(values) if values else NAN

    def contacts_max(self, row, suffix):
        values = [self.value(row, c) for c in self.columns if c.endswith(csv_column(suffix))]
        values = [v for v in values if math.isfinite(v)]
        return max(values) if values else NAN

    def impact_velocity(self, row):
        return self.contacts_max(row, ".max_impact_velocity [m/s]")


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


# ---------------------------------------------------------------------------------------- kinds
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
