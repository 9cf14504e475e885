"""Input of scripts/sweep_charts.py: the plan and the results of a `kimp sweep` output directory
(sweep.h5, sweep.csv, dsrss_table.csv) as a Sweep, with scene key names, units and number
formatting for the charts and summary.md."""
import csv
import json
import math
import os
import re

import h5py
import numpy as np

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
