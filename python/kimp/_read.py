"""kimp.read(): any kimp HDF5 results file (lumped.h5, fem.h5, fit.h5, collide.h5, sweep.h5,
study.h5; layout in docs/architecture.md "Results files") as Python objects, through h5py.

Groups become Group objects (item and attribute access, ``attrs``, ``status``); a time series
group {step, time, value} becomes a TimeSeries; datasets become numpy arrays carrying their
``units``; scalar datasets become floats (or ints) carrying ``units``.
"""

import json

import numpy as np


class Array(np.ndarray):
    """A numpy array with the ``units`` attribute of its dataset ("m", "N", "1", ...)."""

    def __new__(cls, values, units=""):
        array = np.asarray(values).view(cls)
        array.units = units
        return array

    def __array_finalize__(self, obj):
        self.units = getattr(obj, "units", "")


class Float(float):
    """A float with ``units``."""

    def __new__(cls, value, units=""):
        number = super().__new__(cls, value)
        number.units = units
        return number

    def __repr__(self):
        return f"{float(self)!r} {self.units}".rstrip()


class Int(int):
    """An int with ``units``."""

    def __new__(cls, value, units=""):
        number = super().__new__(cls, value)
        number.units = units
        return number


class TimeSeries:
    """Samples of a quantity: time (s), value ([n] or [n][width], in ``units``), step."""

    def __init__(self, step, time, value, units):
        self.step = step
        self.time = time
        self.value = value
        self.units = units

    def __len__(self):
        return len(self.time)

    def __repr__(self):
        return f"TimeSeries({len(self)} samples, value {self.value.shape} {self.units})"


def _text(value):
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray) and value.dtype.kind in "SO":
        return [_text(v) for v in value.tolist()]
    if isinstance(value, np.generic):
        return value.item()
    return value


class Group:
    """A group of the results file: ``g["name"]`` or ``g.name``, ``keys()``, ``attrs``."""

    def __init__(self, name, attrs, members):
        self.name = name
        self.attrs = attrs
        self._members = members

    def __getitem__(self, path):
        """The member at `path` ("lumped/default/peaks"); a time series' datasets are reached
        by their names in the file ("history/displacement/value", ".../time", ".../step").
        KeyError naming the path and the members there if there is none."""
        node, walked = self, self.name.rstrip("/")
        for part in path.strip("/").split("/"):
            if isinstance(node, Group) and part in node._members:
                node = node._members[part]
            elif isinstance(node, TimeSeries) and part in ("step", "time", "value"):
                node = getattr(node, part)
            else:
                members = (list(node._members) if isinstance(node, Group) else
                           ["step", "time", "value"] if isinstance(node, TimeSeries) else [])
                raise KeyError(f"no '{part}' in {walked or '/'} (members: "
                               f"{', '.join(members) or 'none, it is a dataset'})")
            walked += "/" + part
        return node

    def __getattr__(self, name):
        members = self.__dict__.get("_members", {})
        if name in members:
            return members[name]
        raise AttributeError(name)

    def __contains__(self, name):
        return name in self._members

    def __iter__(self):
        return iter(self._members)

    def keys(self):
        return self._members.keys()

    def values(self):
        return self._members.values()

    def items(self):
        return self._members.items()

    @property
    def status(self):
        """The case status ("ok", "failed: ...") or None for a group without one."""
        return self.attrs.get("status")

    def __dir__(self):
        return list(super().__dir__()) + [k for k in self._members if k.isidentifier()]

    def __repr__(self):
        return f"Group({self.name!r}: {', '.join(self._members)})"


class ResultsFile(Group):
    """A whole results file: the groups plus ``meta`` (attributes of /meta), ``scene`` (the
    scene text of /input/scene) and ``resolved`` (the resolved parameters, SI)."""

    def __init__(self, path, group):
        super().__init__("/", group.attrs, group._members)
        self.path = path
        self.meta = group["meta"].attrs if "meta" in group else {}
        self.scene = self._input("scene")
        resolved = self._input("resolved")
        self.resolved = json.loads(resolved) if resolved else None

    def _input(self, name):
        if "input" in self._members and name in self._members["input"]:
            value = self._members["input"][name]
            return value if isinstance(value, str) else _text(value)
        return None

    def __repr__(self):
        return f"ResultsFile({self.path!r}: {', '.join(self._members)})"


def _dataset(dataset):
    units = _text(dataset.attrs.get("units", ""))
    value = dataset[()]
    if isinstance(value, bytes) or (isinstance(value, np.ndarray) and value.dtype.kind in "SO"):
        return _text(value)
    value = np.asarray(value)
    if value.ndim == 0 and value.dtype.kind in "fiu":
        number = value.item()
        return Int(number, units) if value.dtype.kind in "iu" else Float(number, units)
    return Array(value, units)


def _node(h5py, obj):
    attrs = {key: _text(value) for key, value in obj.attrs.items()}
    if isinstance(obj, h5py.Dataset):
        return _dataset(obj)
    names = set(obj.keys())
    if {"time", "value"} <= names and all(isinstance(obj[n], h5py.Dataset) for n in names):
        value = obj["value"]
        units = _text(value.attrs.get("units", attrs.get("units", "")))
        step = obj["step"][()] if "step" in names else None
        return TimeSeries(step, Array(obj["time"][()], "s"), Array(value[()], units), units)
    members = {name: _node(h5py, obj[name]) for name in obj.keys()}
    return Group(obj.name, attrs, members)


def read(path):
    """Open a kimp HDF5 results file as Python objects (see the module documentation).

    >>> r = kimp.read("out/lumped.h5")
    >>> r["lumped/default/history/displacement"].value   # numpy array, units "m"
    """
    import h5py

    with h5py.File(path, "r") as f:
        return ResultsFile(str(path), _node(h5py, f))
