"""The impact laws 1-7 of docs/physics.md §1 as Python objects over the C++ laws.

Each class is made from the law's traits (lumped/laws/law_traits.h, through kimp._kimp.law_traits:
name, parameters and their defaults) and makes the law through the engine's factory
(lumped::make_force_law), so the numbers are the solver's. Stiffness k is in N/m^n (n = the law's exponent) or a unit text ("2500 kN/mm",
"750 kN/mm^1.5"); m_eff in kg or "144.8 t". Sign convention of kimp: δ = interpenetration (m,
> 0 in contact), δ̇ > 0 while closing (m/s), F ≥ 0 compressive (N).

    >>> kv = kimp.laws.KelvinVoigt(k="2500 kN/mm", cor=kimp.thesis_cor, m_eff=144.8e3)
    >>> kv.force(np.linspace(0, 0.01, 5), 0.5)     # vectorised over numpy arrays
"""

import inspect

import numpy as np

from . import _kimp
from ._scene import stiffness_si_unit


def _si(value, unit):
    if value is None:
        return None
    if isinstance(value, str):
        return _kimp.parse_quantity(value, unit)
    return float(value)


class Law:
    """A contact law: ``force(δ, δ̇)`` (N) and its tangents, vectorised over numpy arrays.

    force(), stiffness() and damping() evaluate every sample as a first trial from the virgin
    state (no history): a law that needs the impact velocity (laws 5-7) takes it from that δ̇.
    path() walks a history sample by sample, committing each one (permanent indentation, the
    restitution branch of the hysteretic laws).
    """

    law = ""
    default_exponent = 1.0
    _traits = {"parameters": []}

    def __init__(self, k, cor=_kimp.thesis_cor, m_eff=0.0, exponent=None, ye=False, a1=None,
                 delta_u=0.0, k_w=0.0):
        self.exponent = float(exponent) if exponent is not None else self.default_exponent
        self.k = _si(k, stiffness_si_unit(self.exponent))
        self.cor = _si(cor, "")
        self.m_eff = _si(m_eff, "kg")
        self.ye = bool(ye)
        self.a1 = _si(a1, "s/m")
        self.delta_u = _si(delta_u, "m")
        self.k_w = _si(k_w, "N/m")
        self._given_exponent = exponent
        self._compiled = None

    def _make(self, m_eff=None):
        """The C++ law, with `m_eff` (kg) instead of this law's own if given."""
        return _kimp.Law(self.law, self.k, self._given_exponent, self.cor,
                         self.m_eff if m_eff is None else m_eff, self.ye, self.a1, self.delta_u,
                         self.k_w)

    @property
    def _law(self):
        # Made on first use: a law for kimp.collide() may leave m_eff to the collision.
        if self._compiled is None:
            self._compiled = self._make()
        return self._compiled

    def force(self, delta, delta_dot):
        """Contact force F (N, compressive > 0) at interpenetration δ (m) and rate δ̇ (m/s)."""
        return self._law.force(delta, delta_dot)

    def stiffness(self, delta, delta_dot):
        """dF/dδ (N/m) at (δ, δ̇), the exact tangent the Newmark integrator uses."""
        return self._law.stiffness(delta, delta_dot)

    def damping(self, delta, delta_dot):
        """dF/dδ̇ (N·s/m) at (δ, δ̇)."""
        return self._law.damping(delta, delta_dot)

    def path(self, delta, delta_dot):
        """F (N) along a history δ(t) (m), δ̇(t) (m/s), committing every sample in order."""
        return self._law.path(np.asarray(delta, float), np.asarray(delta_dot, float))

    def stability_stiffness(self, max_deformation):
        """k_t (N/m) bounding the central-difference step up to `max_deformation` (m)."""
        return self._law.stability_stiffness(float(max_deformation))

    def __repr__(self):
        # The law's parameters in the order of its traits; the exponent is shown as n.
        shown = [("n" if name == "exponent" else name, getattr(self, name),
                  stiffness_si_unit(self.exponent) if unit == "N/m^n" else unit)
                 for name, unit, _required, _default in self._traits["parameters"]]
        shown = [(key, value, unit) for key, value, unit in shown if value is not None]
        text = ", ".join(f"{key}={value!r}" if isinstance(value, bool) else f"{key}={value:.6g}"
                         for key, value, _unit in shown)
        told = ", ".join(f"{key} in {unit}" for key, _value, unit in shown
                         if unit not in ("", "flag"))
        return f"{type(self).__name__}({text}) [{told}]"


def _law_class(traits):
    """The class of one law, made from its traits (lumped/laws/law_traits.h): its keyword
    arguments are the law's parameters in order, with their defaults."""
    signature = inspect.Signature(
        [inspect.Parameter("self", inspect.Parameter.POSITIONAL_OR_KEYWORD)] +
        [inspect.Parameter(name, inspect.Parameter.POSITIONAL_OR_KEYWORD,
                           **({} if required else {"default": default}))
         for name, _unit, required, default in traits["parameters"]])

    def __init__(self, *args, **kwargs):
        bound = signature.bind(self, *args, **kwargs)
        bound.apply_defaults()
        values = dict(bound.arguments)
        del values["self"]
        Law.__init__(self, **values)

    __init__.__signature__ = signature
    return type(traits["class_name"], (Law,), {
        "__doc__": traits["summary"], "__init__": __init__, "__module__": __name__,
        "law": traits["name"], "default_exponent": traits["default_exponent"],
        "_traits": traits})


_CLASSES = {traits["name"]: _law_class(traits) for traits in _kimp.law_traits()}
globals().update({cls.__name__: cls for cls in _CLASSES.values()})
__all__ = ["Law"] + [cls.__name__ for cls in _CLASSES.values()] + ["make", "names"]


def names():
    """The law names of the scene files, in the order of docs/physics.md §1."""
    return list(_kimp.force_law_names())


def make(name, **parameters):
    """The law called `name` in scene files ("kelvin_voigt", ...) with keyword parameters."""
    try:
        cls = _CLASSES[name]
    except KeyError:
        raise ValueError(f"unknown law '{name}' (known: {', '.join(names())})") from None
    return cls(**parameters)
