"""Scenes: YAML text validated by the CLI's own reader (kimp._kimp.validate_scene).

A Scene keeps the scene text, its name in messages and its kind ("lumped", "collide", "fem",
"study"); every construction validates it exactly as ``kimp <kind> SCENE.yaml`` would, so a bad
scene raises SceneError with the CLI's message.
"""

import copy
import functools
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

# The location a message starts with: "FILE:LINE:COLUMN: " (YAML syntax), "FILE:LINE: " or
# "FILE: " (a file that cannot be read).
_LOCATION = re.compile(r"^(?P<file>.*?)(?::(?P<line>\d+)(?::(?P<column>\d+))?)?: ")
_LINE = re.compile(r"^:(?P<line>\d+)(?::(?P<column>\d+))?: ")
# What follows the location: "KEY = VALUE: rule", "KEY: problem", "unknown key 'K'[ in PATH]",
# "duplicate key 'PATH'".
_KEY = re.compile(r"^(?:unknown key '(?P<unknown>[^']*)'(?: in (?P<parent>[\w.\[\]]+))?"
                  r"|duplicate key '(?P<duplicate>[^']*)'"
                  r"|(?P<key>[\w]+(?:[.\[][\w\]]*)*)(?: = |: ))")

# Default exponent n of each law (the unit N/m^n of a bare SI k): the laws' traits.
_LAW_EXPONENT = {traits["name"]: traits["default_exponent"] for traits in _kimp.law_traits()}


def stiffness_si_unit(n):
    """The SI unit N/m^n of a stiffness of exponent n ("N/m" for n = 1), as the scenes read it."""
    return f"N/m^{float(n)!r}" if float(n) != 1.0 else "N/m"


class SceneError(ValueError):
    """A scene the CLI would refuse; str(error) is the CLI's message (without "error: ").

    Attributes of the message's first failure: ``file`` (the name given to the reader: the path
    of a file, "<dict>", "NAME (with_)"), ``line`` and ``column`` (1-based, 0 if unknown) and
    ``key`` (its key path, e.g. "walls.left.gap" or "cases[0].record"; "" if it names none).
    The line of a scene made by from_dict() or with_() is a line of its to_yaml() text.
    """

    def __init__(self, message, file=None):
        super().__init__(message)
        first = message.splitlines()[0] if message else ""
        self.file, self.line, self.column, self.key = "", 0, 0, ""
        rest = None
        if file and first.startswith(file + ":"):
            # The reader's name is known: file names with a colon are told apart.
            self.file = file
            rest = first[len(file):]
            match = _LINE.match(rest)
            if match:
                self.line = int(match.group("line"))
                self.column = int(match.group("column") or 0)
                rest = rest[match.end():]
            elif rest.startswith(": "):
                rest = rest[2:]
            else:
                rest = None
        if rest is None:
            match = _LOCATION.match(first)
            if not match:
                return
            self.file = match.group("file")
            self.line = int(match.group("line") or 0)
            self.column = int(match.group("column") or 0)
            rest = first[match.end():]
        match = _KEY.match(rest)
        if match:
            if match.group("unknown") is not None:
                parent = match.group("parent")
                self.key = f"{parent}.{match.group('unknown')}" if parent else match.group(
                    "unknown")
            else:
                self.key = match.group("duplicate") or match.group("key") or ""


def _validate(kind, text, name, directory=None):
    try:
        return _kimp.validate_scene(kind, text, name, directory)
    except (_kimp.SceneError, _kimp.UnitError) as error:
        raise SceneError(str(error), name) from None


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


@functools.lru_cache(maxsize=None)
def _si_unit(unit):
    return _kimp.si_unit(unit)


def _si_text(value, unit):
    """A number in SI as quantity text in the scene grammar (read back bit for bit)."""
    si = _si_unit(unit)
    text = repr(float(value))
    return text if si == "1" and unit in ("", "1") else f"{text} {si}"


def _stiffness_unit(section):
    law = section.get("law", "") if isinstance(section, dict) else ""
    n = section.get("exponent") if isinstance(section, dict) else None
    if not _number(n):
        n = _LAW_EXPONENT.get(law, 1.0)
    return stiffness_si_unit(n)


def _to_text_values(kind, data, prefix=""):
    """Turn SI numbers given for quantity (and stiffness, time step) keys into unit texts (new
    dicts and lists; `data` is not changed)."""
    if isinstance(data, list):
        return [_to_text_values(kind, item, prefix + "[]") for item in data]
    if not isinstance(data, dict):
        return data
    return {key: _text_value(kind, data, key, value, f"{prefix}.{key}" if prefix else str(key))
            for key, value in data.items()}


def _text_value(kind, section, key, value, path):
    """`value` of `key` in the dict `section` (at key path `path`) as the scene text holds it."""
    if isinstance(value, list) and _schema(kind).get(path, ("", ""))[0] == "quantity_list":
        unit = _schema(kind)[path][1]
        return [_si_text(v, unit) if _number(v) else v for v in value]
    if isinstance(value, (dict, list)):
        return _to_text_values(kind, value, path)
    if not _number(value):
        return value
    kind_of_key, unit = _schema(kind).get(path, ("", ""))
    if "quantity" in kind_of_key:
        return _si_text(value, unit)
    if kind_of_key == "text" and key in ("k", "k_b"):
        return f"{float(value)!r} {_stiffness_unit(section)}"
    if kind_of_key == "text" and key == "dt":
        return f"{float(value)!r} s"
    if type(value).__module__ == "numpy":
        return value.item() if hasattr(value, "item") else value
    return value


def _merged(node, keys, value):
    """A copy of the nested dict `node` with the key path `keys` set to `value` (a dict value
    merges key by key, its keys may be dotted paths too). Only the dicts along the path are
    copied: the rest is shared with `node`, which is left unchanged."""
    out = dict(node) if isinstance(node, dict) else {}
    key = keys[0]
    if len(keys) > 1:
        out[key] = _merged(out.get(key), keys[1:], value)
    elif isinstance(value, dict):
        sub = out.get(key) if isinstance(out.get(key), dict) else {}
        for sub_key, sub_value in value.items():
            sub = _merged(sub, str(sub_key).split("."), sub_value)
        out[key] = sub
    else:
        out[key] = value
    return out


_WITH = " (with_)"


class Scene:
    """A validated scene of one kind (the file of ``kimp <kind> SCENE.yaml``).

    Values may be given as unit texts ("600 MN/m", "15 cm", "5 %") or, in from_dict() and
    with_(), as plain numbers in SI (N/m, m, 1 for ratios: 0.05 is 5 %).
    """

    def __init__(self, text="", name="<scene>", kind="lumped", _data=None, directory=None):
        """A scene of `text` named `name` in messages; its relative paths (records, k tables)
        are relative to `directory` (default: the directory of the file `name`, if it is one,
        else the working directory)."""
        self.kind = kind
        self.name = name
        self.text = text
        self.directory = None if directory is None else os.fspath(directory)
        self._parsed = _validate(kind, text, name, self.directory)
        self._data = _data  # the dict `text` was dumped from, if any (never changed)
        self._texts = _data  # the scene as nested dicts of unit texts, made on first with_()

    @classmethod
    def from_yaml(cls, path, kind="lumped"):
        """Read a scene file; `path` is named in error messages as given (like the CLI)."""
        name = os.fspath(path)
        try:
            text = _kimp.read_text_file(name)
        except _kimp.SceneError as error:
            raise SceneError(str(error), name) from None
        return cls(text, name, kind, directory=os.path.dirname(name))

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
        ``scene.with_(**{"walls.left.gap": "10 cm"})`` or ``scene.with_(impact={"cor": 0.5})``.

        The new scene's text is written anew (its to_yaml()), so it is named "NAME (with_)":
        the lines of its error messages are lines of that text, not of the original file. Its
        relative paths stay relative to the original file's directory."""
        if self._texts is None:
            self._texts = _to_text_values(self.kind, self.to_dict())
        # Only the dicts along the changed paths are new (the rest is shared, never changed),
        # and only the changed top-level sections are converted to unit texts.
        data, changed = self._texts, set()
        for path, value in {**(overrides or {}), **kwargs}.items():
            keys = str(path).split(".")
            data = _merged(data, keys, value)
            changed.add(keys[0])
        for key in changed:
            data[key] = _text_value(self.kind, data, key, data[key], key)
        name = self.name if self.name.endswith(_WITH) else self.name + _WITH
        return Scene(_dump(data), name, self.kind, data, self._base_directory())

    def _base_directory(self):
        """The directory this scene's relative paths are resolved against ("" = working
        directory); looked up once."""
        if self.directory is None:
            self.directory = os.path.dirname(self.name) if os.path.isfile(self.name) else ""
        return self.directory

    def write(self, path):
        """Write the scene text to `path`."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.text)

    def __repr__(self):
        lines = self.text.count("\n")
        return f"Scene(kind={self.kind!r}, name={self.name!r}, {lines} lines)"
