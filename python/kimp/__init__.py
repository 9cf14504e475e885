"""kimp from Python: scenes, lumped pounding runs, impact laws, collisions, ground motions, fits,
FEM runs and studies over the same C++ engines as the ``kimp`` command, plus a reader of every
kimp HDF5 results file.

    >>> import kimp
    >>> scene = kimp.Scene.from_yaml("data/scenes/isolated_4storey_no_walls.yaml")
    >>> kimp.lumped(scene).peaks
    >>> kimp.lumped(scene.with_(**{"walls.left.gap": "10 cm"})).n_impacts

Units: SI floats everywhere (m, s, kg, N, N/m^n, J); inputs also accept unit texts parsed by
kimp's own unit reader ("600 MN/m", "15 cm", "0.4 g"). See docs/guide/python.md.
"""

from . import _kimp, laws
from ._read import Array, Float, Group, Int, ResultsFile, TimeSeries, read
from ._runs import (Collision, Contact, CorRow, Energy, FitResult, GroundMotion, History,
                    Parameter, Peaks, PlanResult, Result, Results, Wall, collide, cor_table, fem,
                    fit, ground_motion, lumped, pushover, study)
from ._scene import Scene, SceneError

#: The thesis' nominal coefficient of restitution, the default COR of every law and fit.
thesis_cor = float(_kimp.thesis_cor)

#: True when this build has the FEM engine (kimp.fem, kimp.study).
with_fem = bool(_kimp.with_fem)


def set_verbosity(level):
    """What the engines log on stderr: "quiet" (warnings and errors: the default of the module,
    as ``kimp -q``), "normal" (also each run's progress, as the CLI without -q) or "verbose"."""
    _kimp.set_verbosity(level)


set_verbosity("quiet")


def parse_quantity(text, unit):
    """SI value of a quantity text ("600 MN/m") that must have the dimension of `unit`."""
    return _kimp.parse_quantity(text, unit)


def format_quantity(value, unit):
    """An SI value as text in `unit` (15 significant digits): format_quantity(6e8, "MN/m")."""
    return _kimp.format_quantity(float(value), unit)


__all__ = ["Scene", "SceneError", "lumped", "PlanResult", "Result", "Results", "Peaks", "History", "Contact", "Wall",
           "Energy", "ground_motion", "GroundMotion", "collide", "Collision", "cor_table", "CorRow", "fit",
           "FitResult", "Parameter", "fem", "pushover", "study", "read", "ResultsFile", "Group",
           "TimeSeries", "Array", "Float", "Int", "laws", "thesis_cor", "with_fem", "parse_quantity",
           "format_quantity", "set_verbosity"]
