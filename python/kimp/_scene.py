"""Scenes: YAML text validated by the CLI's own reader (kimp._kimp.validate_scene).

A Scene keeps the scene text, its name in messages and its kind ("lumped", "collide", "fem",
"study"); every construction validates it exactly as ``kimp <kind> SCENE.yaml`` would, so a bad
scene raises SceneError with the CLI's message.
"""

import copy
import json
import os
import re

import yaml

_Loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def _dump(data):
    """Scene text of nested dicts: JSON, which YAML reads, one key per line (so messages name a
    line), ten times faster to write than YAML in a loop of thousands of runs."""
    return json.dumps(data, indent=2) + "\n"

from . import _kimp

# "FILE:LINE: key = value: rule" or "FILE:LINE: message" (first failure of the message).
_LOCATION = re.compile(r"^(?P<file>.*?):(?P<line>\d+): (?:(?P<key>[\w.\[\]]+) = )?")

# Default exponent n of each law (the unit N/m^n of a bare SI k), docs/physics.md §1.
_LAW_EXPONENT = {"hertzdamp": 1.5, "hysteretic": 1.5, "jankowski": 1.5, "bumper": 2.65}


class SceneError(ValueError):
    """A scene the CLI would refuse; str(error) is the CLI's message (without "error: ").

    Attributes: ``file`` (name given to the reader), ``line`` (1-based, 0 if unknown) and ``key``
    (key path of the first failure, "" if the message names none).
    """

    def __init__(self, message):
        super().__init__(message)
        first = message.splitlines()[0] if message else ""
        match = _LOCATION.match(first)
        self.file = match.group("file") if match else ""
        self.line = int(match.group("line")) if match else 0
        self.key = (match.group("key") or "") if match else ""


def _validate(kind, text, name):
    try:
        return _kimp.validate_scene(kind, text, name)
    except (_kimp.SceneError, _kimp.UnitError) as error:
        raise SceneError(str(error)) from None


_schemas = {}


def _schema(kind):
    """key path -> (type, display unit) of every key of the scene kind (list items as "a[].b")."""
    if kind not in _schemas:
        table = {}

        def walk(keys):
            for key in keys:
                table[key["path"]] = (key["type"], key.get("unit", ""))
                walk(key.get("keys", []))
                if isinstance(key.get("item"), list):
                    walk(key["item"])

        walk(json.loads(_kimp.scene_schema(kind))["keys"])
        _schemas[kind] = table
    return _schemas[kind]


def _number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) or (
        type(value).__module__ == "numpy" and getattr(value, "shape", None) == ())


def _si_text(value, unit):
    """A number in SI as quantity text in the scene grammar (read back bit for bit)."""
    si = _kimp.si_unit(unit)
    text = repr(float(value))
    return text if si == "1" and unit in ("", "1") else f"{text} {si}"


def _stiffness_unit(section):
    law = section.get("law", "") if isinstance(section, dict) else ""
    n = section.get("exponent") if isinstance(section, dict) else None
    if not _number(n):
        n = _LAW_EXPONENT.get(law, 1.0)
    return f"N/m^{float(n)!r}" if float(n) != 1.0 else "N/m"


def _to_text_values(kind, data, prefix=""):
    """Turn SI numbers given for quantity (and stiffness, time step) keys into unit texts."""
    schema = _schema(kind)
    if isinstance(data, list):
        return [_to_text_values(kind, item, prefix + "[]") for item in data]
    if not isinstance(data, dict):
        return data
    out = {}
    for key, value in data.items():
        path = f"{prefix}.{key}" if prefix else str(key)
        kind_of_key, unit = schema.get(path, ("", ""))
        if isinstance(value, (dict, list)):
            out[key] = _to_text_values(kind, value, path)
        elif _number(value) and "quantity" in kind_of_key:
            out[key] = _si_text(value, unit)
        elif _number(value) and kind_of_key == "text" and key in ("k", "k_b"):
            out[key] = f"{float(value)!r} {_stiffness_unit(data)}"
        elif _number(value) and kind_of_key == "text" and key == "dt":
            out[key] = f"{float(value)!r} s"
        elif type(value).__module__ == "numpy":
            out[key] = value.item() if hasattr(value, "item") else value
        else:
            out[key] = value
    return out


def _merge(base, path, value):
    """Set the dotted key `path` of the nested dict `base` (nested dicts merge key by key)."""
    keys = path.split(".")
    node = base
    for key in keys[:-1]:
        if not isinstance(node.get(key), dict):
            node[key] = {}
        node = node[key]
    last = keys[-1]
    if isinstance(value, dict):
        if not isinstance(node.get(last), dict):
            node[last] = {}
        for sub, sub_value in value.items():
            _merge(node[last], sub, sub_value)
    else:
        node[last] = value


class Scene:
    """A validated scene of one kind (the file of ``kimp <kind> SCENE.yaml``).

    Values may be given as unit texts ("600 MN/m", "15 cm", "5 %") or, in from_dict() and
    with_(), as plain numbers in SI (N/m, m, 1 for ratios: 0.05 is 5 %).
    """

    def __init__(self, text="", name="<scene>", kind="lumped", _data=None):
        self.kind = kind
        self.name = name
        self.text = text
        self._parsed = _validate(kind, text, name)
        self._data = _data  # the dict `text` was dumped from, if any

    @classmethod
    def from_yaml(cls, path, kind="lumped"):
        """Read a scene file; `path` is named in error messages as given (like the CLI)."""
        name = os.fspath(path)
        try:
            text = _kimp.read_text_file(name)
        except _kimp.SceneError as error:
            raise SceneError(str(error)) from None
        return cls(text, name, kind)

    @classmethod
    def from_dict(cls, data, kind="lumped", name="<dict>"):
        """A scene from nested dicts as the YAML would hold them (SI numbers allowed)."""
        data = _to_text_values(kind, data or {})
        return cls(_dump(data), name, kind, data)

    @classmethod
    def default(cls, kind="lumped"):
        """The default scene of the kind (every key at its default)."""
        return cls("", f"<default {kind} scene>", kind)

    @staticmethod
    def defaults_text(kind="lumped"):
        """The annotated default scene (``kimp <kind> --print-defaults``)."""
        return _kimp.default_scene(kind)

    def to_yaml(self):
        """The scene text, exactly as validated (a scene made from dicts is written in JSON
        syntax, which YAML and the CLI read)."""
        return self.text

    def to_dict(self):
        """The scene as nested dicts (only the keys written in the text)."""
        if self._data is not None:
            return copy.deepcopy(self._data)
        return yaml.load(self.text, Loader=_Loader) or {}

    @property
    def resolved(self):
        """Every parameter after defaults, in SI (the /input/resolved of the results file)."""
        return json.loads(self._parsed.resolved)

    def with_(self, overrides=None, **kwargs):
        """A new scene with keys replaced: dotted paths or nested dicts, e.g.
        ``scene.with_(**{"walls.left.gap": "10 cm"})`` or ``scene.with_(impact={"cor": 0.5})``."""
        data = self.to_dict()
        for path, value in {**(overrides or {}), **kwargs}.items():
            _merge(data, path, value)
        data = _to_text_values(self.kind, data)
        return Scene(_dump(data), self.name, self.kind, data)

    def write(self, path):
        """Write the scene text to `path`."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.text)

    def __repr__(self):
        lines = self.text.count("\n")
        return f"Scene(kind={self.kind!r}, name={self.name!r}, {lines} lines)"
