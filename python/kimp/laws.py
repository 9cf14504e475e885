"""The impact laws 1-7 of docs/physics.md §1 as Python objects over the C++ laws.

Each class makes the law through the engine's factory (lumped::make_force_law), so the numbers are
the solver's. Stiffness k is in N/m^n (n = the law's exponent) or a unit text ("2500 kN/mm",
"750 kN/mm^1.5"); m_eff in kg or "144.8 t". Sign convention of kimp: δ = interpenetration (m,
> 0 in contact), δ̇ > 0 while closing (m/s), F ≥ 0 compressive (N).

    >>> kv = kimp.laws.KelvinVoigt(k="2500 kN/mm", cor=0.7, m_eff=144.8e3)
    >>> kv.force(np.linspace(0, 0.01, 5), 0.5)     # vectorised over numpy arrays
"""

import numpy as np

from . import _kimp

__all__ = ["Law", "Linear", "KelvinVoigt", "ModifiedKelvinVoigt", "Jankowski", "Hertzdamp",
           "Hysteretic", "Bumper", "make", "names"]


def _si(value, unit):
    if value is None:
        return None
    if isinstance(value, str):
        return _kimp.parse_quantity(value, unit)
    return float(value)


def _stiffness_unit(n):
    return "N/m" if n == 1.0 else f"N/m^{n!r}"


class Law:
    """A contact law: ``force(δ, δ̇)`` (N) and its tangents, vectorised over numpy arrays.

    force(), stiffness() and damping() evaluate every sample as a first trial from the virgin
    state (no history): a law that needs the impact velocity (laws 5-7) takes it from that δ̇.
    path() walks a history sample by sample, committing each one (permanent indentation, the
    restitution branch of the hysteretic laws).
    """

    law = ""
    default_exponent = 1.0

    def __init__(self, k, cor=0.7, m_eff=0.0, exponent=None, ye=False, a1=None, delta_u=0.0,
                 k_w=0.0):
        self.exponent = float(exponent) if exponent is not None else self.default_exponent
        self.k = _si(k, _stiffness_unit(self.exponent))
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

    def _parameters(self):
        return {"k": self.k, "cor": self.cor, "m_eff": self.m_eff}

    def __repr__(self):
        parameters = self._parameters()
        text = ", ".join(f"{key}={value!r}" if isinstance(value, bool) else f"{key}={value:.6g}"
                         for key, value in parameters.items() if value is not None)
        units = {"k": _stiffness_unit(self.exponent), "m_eff": "kg", "a1": "s/m", "delta_u": "m",
                 "k_w": "N/m"}
        told = ", ".join(f"{key} in {unit}" for key, unit in units.items()
                         if parameters.get(key) is not None)
        return f"{type(self).__name__}({text}) [{told}]"


class Linear(Law):
    """Law 1, linear spring: F = kδ (k in N/m)."""

    law = "linear"

    def __init__(self, k):
        super().__init__(k)

    def _parameters(self):
        return {"k": self.k}


class KelvinVoigt(Law):
    """Law 2, Kelvin-Voigt: F = kδ + cδ̇, c = 2ξ√(k·m_eff), ξ = −ln e/√(π² + ln² e) (k in N/m)."""

    law = "kelvin_voigt"

    def __init__(self, k, cor=0.7, m_eff=0.0):
        super().__init__(k, cor, m_eff)


class ModifiedKelvinVoigt(Law):
    """Law 3, Kelvin-Voigt without tension (ends the contact, keeps a permanent set)."""

    law = "modified_kelvin_voigt"

    def __init__(self, k, cor=0.7, m_eff=0.0):
        super().__init__(k, cor, m_eff)


class Jankowski(Law):
    """Law 4, Jankowski's non-linear viscoelastic law: k in N/m^1.5, damping only on approach."""

    law = "jankowski"
    default_exponent = 1.5

    def __init__(self, k, cor=0.7, m_eff=0.0):
        super().__init__(k, cor, m_eff)


class Hertzdamp(Law):
    """Law 5, Hertzdamp (Muthukumar & DesRoches): F = kδ^n·(1 + β·δ̇/v_imp), k in N/m^n, n = 1.5
    by default, β = 3(1 − e²)/4 (ye=True: Ye et al.'s β = 8(1 − e)/(5e)); no m_eff."""

    law = "hertzdamp"
    default_exponent = 1.5

    def __init__(self, k, cor=0.7, exponent=1.5, ye=False):
        super().__init__(k, cor, 0.0, exponent, ye)

    def _parameters(self):
        return {"k": self.k, "cor": self.cor, "n": self.exponent, "ye": self.ye}


class Hysteretic(Law):
    """Law 6, hysteretic (C_imp of eq. 2.23, or a1·(1 − e²)): k in N/m^n, n = 1.5 by default."""

    law = "hysteretic"
    default_exponent = 1.5

    def __init__(self, k, cor=0.7, m_eff=0.0, exponent=1.5, a1=None):
        super().__init__(k, cor, m_eff, exponent, a1=a1)

    def _parameters(self):
        return {"k": self.k, "cor": self.cor, "m_eff": self.m_eff, "n": self.exponent,
                "a1": self.a1}


class Bumper(Law):
    """Law 7, rubber bumper: hysteretic with n = 2.65 up to δ_u (m), then the wall k_w (N/m)."""

    law = "bumper"
    default_exponent = 2.65

    def __init__(self, k, cor=0.7, m_eff=0.0, delta_u=0.0375, k_w=1.5e9, exponent=2.65, a1=None):
        super().__init__(k, cor, m_eff, exponent, a1=a1, delta_u=delta_u, k_w=k_w)

    def _parameters(self):
        return {"k": self.k, "cor": self.cor, "m_eff": self.m_eff, "n": self.exponent,
                "delta_u": self.delta_u, "k_w": self.k_w}


_CLASSES = {cls.law: cls for cls in (Linear, KelvinVoigt, ModifiedKelvinVoigt, Jankowski,
                                      Hertzdamp, Hysteretic, Bumper)}


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
