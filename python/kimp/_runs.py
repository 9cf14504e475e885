"""Runs from Python: lumped cases, ground motions, collisions, fits, FEM and studies.

Every function calls the engine through kimp._kimp (the GIL is released while C++ runs) and
returns plain dataclasses holding numpy arrays; all values are SI (units in each docstring).
"""

import math
import os
import tempfile
from dataclasses import dataclass, field
from typing import Dict, List, Optional

import numpy as np

from . import _kimp
from ._read import read
from ._scene import Scene, SceneError


def _short(array):
    return np.array2string(np.asarray(array), precision=4, threshold=8, separator=", ")


@dataclass(repr=False)
class Peaks:
    """Peaks per floor: displacement (m, relative to the ground, per DOF: isolation level first),
    absolute acceleration (m/s², per DOF), interstorey drift (m, per storey)."""

    displacement: np.ndarray
    absolute_acceleration: np.ndarray
    interstorey_drift: np.ndarray

    def __repr__(self):
        return (f"Peaks(displacement={_short(self.displacement)} m, "
                f"absolute_acceleration={_short(self.absolute_acceleration)} m/s², "
                f"interstorey_drift={_short(self.interstorey_drift)} m)")


@dataclass(repr=False)
class History:
    """Histories at the output interval, row = sample: time (s, n), displacement (m, n × DOFs),
    absolute_acceleration (m/s², n × DOFs), interstorey_drift (m, n × storeys), contact_force
    (impact force, N, n × contacts), energy_input (J, n), energy_error (1, n), isolator_force
    (the isolator's force on the base, N, n; zeros without isolator) and hysteretic_energy (the
    isolator's dissipated energy so far, J, n). isolator_force against displacement[:, 0] is the
    isolator's hysteresis loop."""

    time: np.ndarray
    displacement: np.ndarray
    absolute_acceleration: np.ndarray
    interstorey_drift: np.ndarray
    contact_force: np.ndarray
    energy_input: np.ndarray
    energy_error: np.ndarray
    isolator_force: np.ndarray
    hysteretic_energy: np.ndarray

    def __repr__(self):
        n = len(self.time)
        end = self.time[-1] if n else 0.0
        return (f"History({n} samples to t = {end:g} s; displacement {self.displacement.shape}, "
                f"contact_force {self.contact_force.shape})")


@dataclass
class Contact:
    """One contact pair: peak force (N), impacts (first-contact times, s, and closing rates,
    m/s), permanent indentation (m) and the work the law dissipated (J)."""

    name: str
    peak_force: float
    impact_time: np.ndarray = field(repr=False)
    impact_velocity: np.ndarray = field(repr=False)
    permanent_indentation: float
    dissipated_energy: float

    @property
    def n_impacts(self):
        return len(self.impact_time)


@dataclass
class Wall:
    """A yielding moat wall (docs/physics.md §2 "Yielding moat wall"): peak force of its
    wall-and-backfill part (resistance and dashpot), its peak resistance without the dashpot and
    its capacity (N), peak and residual (permanent set) displacement
    into the backfill and the failure limit (m), the time it passed that limit (s; None: it did
    not fail), its plastic and radiated work (J)."""

    name: str
    peak_force: float
    capacity: float
    peak_resistance: float
    peak_displacement: float
    residual_displacement: float
    failure_displacement: float
    failure_time: Optional[float]
    plastic_work: float
    radiated_work: float

    @property
    def failed(self):
        return self.failure_time is not None

    @property
    def peak_resistance_ratio(self):
        """Peak resistance (without the dashpot) over capacity."""
        return self.peak_resistance / self.capacity


@dataclass
class Isolator:
    """The isolator of the main building: its kind ("linear", "bilinear", "friction_pendulum",
    "bouc_wen"), peak force (max |f_iso|, N) and the energy it dissipated (J)."""

    kind: str
    peak_force: float
    dissipated_energy: float


@dataclass
class Energy:
    """Energy balance, J: E_0 + W_in = E_kin + E_strain + E_viscous + E_hyst + W_contact;
    relative errors are dimensionless (docs/physics.md §5)."""

    initial: float
    input: float
    kinetic: float
    strain: float
    viscous: float
    hysteretic: float
    contact_work: float
    impact_dissipated: float
    relative_error: float
    max_relative_error: float
    wall_plastic: float = 0.0
    wall_radiated: float = 0.0


@dataclass(repr=False)
class Result:
    """One case of a lumped scene (the /lumped/<case> group of lumped.h5, in memory).

    dt, dt_critical, duration, wall_time in s; pga in m/s²; `modes` per building block:
    period (s), rayleigh_a (1/s), rayleigh_b (s), c_iso (N·s/m). `status` is "ok" or
    "failed: <reason>" (then peaks, history and energy are None)."""

    name: str
    status: str
    peaks: Optional[Peaks]
    history: Optional[History]
    contacts: List[Contact]
    energy: Optional[Energy]
    dt: float
    n_steps: int
    duration: float
    pga: float
    dt_critical: float
    governing: str
    wall_time: float
    modes: Dict[str, dict]
    contact_names: List[str]
    storey_upper_dofs: List[int]
    companion_peaks: Optional[Peaks] = None
    isolator: Optional[Isolator] = None
    walls: List[Wall] = field(default_factory=list)

    @property
    def ok(self):
        return self.status == "ok"

    @property
    def n_impacts(self):
        """Impacts over all contacts."""
        return sum(c.n_impacts for c in self.contacts)

    @property
    def max_interstorey_drift(self):
        """Largest peak interstorey drift, m (0 without storeys)."""
        drift = self.peaks.interstorey_drift if self.peaks else []
        return float(np.max(drift)) if len(drift) else 0.0

    def __repr__(self):
        if not self.ok:
            return f"Result(name={self.name!r}, status={self.status!r})"
        return (f"Result(name={self.name!r}, {self.n_steps} steps of {self.dt:.4g} s, "
                f"{self.n_impacts} impacts, peak isolation displacement "
                f"{self.peaks.displacement[0]:.4g} m, max drift {self.max_interstorey_drift:.4g} "
                f"m, energy error {self.energy.relative_error:.2g})")


class Results(list):
    """The Results of a scene with several cases, in case order; ``results["name"]`` picks one,
    ``results.peaks`` is {case name: Peaks}."""

    def __getitem__(self, key):
        if isinstance(key, str):
            for result in self:
                if result.name == key:
                    return result
            raise KeyError(f"no case {key!r} (cases: {', '.join(r.name for r in self)})")
        return super().__getitem__(key)

    @property
    def names(self):
        return [r.name for r in self]

    @property
    def peaks(self):
        """{case name: Peaks} (None for a failed case)."""
        return {r.name: r.peaks for r in self}

    def __repr__(self):
        return "Results([\n" + "".join(f"  {r!r},\n" for r in self) + "])"


def _result(d):
    ok = d["status"] == "ok"
    peaks = lambda p: Peaks(**p) if p is not None else None  # noqa: E731
    return Result(
        name=d["name"], status=d["status"],
        peaks=peaks(d.get("peaks")),
        history=History(**d["history"]) if ok else None,
        contacts=[Contact(**c) for c in d.get("contacts", [])],
        energy=Energy(**d["energy"]) if ok else None,
        dt=d.get("dt", 0.0), n_steps=d.get("n_steps", 0), duration=d.get("duration", 0.0),
        pga=d["pga"], dt_critical=d["dt_critical"], governing=d["governing"],
        wall_time=d["wall_time"], modes=d["modes"], contact_names=d["contact_names"],
        storey_upper_dofs=d["storey_upper_dofs"], companion_peaks=peaks(d.get("companion_peaks")),
        isolator=Isolator(**d["isolator"]) if "isolator" in d else None,
        walls=[Wall(**w) for w in d.get("walls", [])])


@dataclass(repr=False)
class PlanResult:
    """One run of a scene in plan (rigid diaphragms: u_x, u_y, θ per level, isolation level
    first). Arrays: ``peaks["displacement"]`` and ``peaks["absolute_acceleration"]`` (levels, 3)
    in m, rad and m/s², rad/s²; ``peaks["corner_displacement"]`` and
    ``peaks["horizontal_acceleration"]`` per level; ``peaks["drift_x"]``, ``["drift_y"]``,
    ``["corner_drift"]`` per storey (m); ``peaks["wall_force"]`` per wall face (N); the headline
    peaks of summary.json (``base_corner_displacement``, ``corner_impact_force``,
    ``friction_force``, ``top_acceleration``, ``isolator_force``). ``history``: ``time`` (n),
    ``displacement`` and ``absolute_acceleration`` (n, levels, 3), ``corner_displacement``
    (n, corners of level 0, 2), ``contact_force`` and ``friction_force`` (n, contacts),
    ``energy_error`` (n). ``contacts``: one dict per contact point; ``energy``: J, with the
    friction work and the work on yielding walls. ``damping``: the superstructure's damping
    model (``"rayleigh"`` or ``"modal"``, the scene's ``plan.damping``), ``damping_ratio`` and
    ``isolation_damping_ratio``. ``yielding_walls``: one dict per yielding wall face (the
    scene's ``plan.moat.yielding``): ``face``, the face's ``peak_force`` and the part's
    ``capacity`` and ``peak_resistance`` (N), ``peak_resistance_ratio``, ``peak_displacement``,
    ``residual_displacement``, ``final_displacement`` and ``failure_displacement`` (m, None: no
    limit),
    ``plastic_work`` and ``radiated_work`` (J), ``failed`` and ``failure_time`` (s, or None)."""

    name: str
    status: str
    ground_motion: str
    dt: float
    dt_critical: float
    n_steps: int
    n_levels: int
    n_impacts: int
    wall_time: float
    contact_names: List[str]
    contacts: List[dict]
    peaks: dict
    history: dict
    energy: dict
    damping: dict
    yielding_walls: List[dict]

    @property
    def ok(self):
        return self.status == "ok"

    @property
    def x(self):
        """History of u_x per level, m: (n, levels)."""
        return self.history["displacement"][:, :, 0]

    @property
    def y(self):
        """History of u_y per level, m: (n, levels)."""
        return self.history["displacement"][:, :, 1]

    @property
    def rotation(self):
        """History of θ per level, rad: (n, levels)."""
        return self.history["displacement"][:, :, 2]

    @property
    def corners(self):
        """History of the displacements of level 0's corners, m: (n, corners, 2)."""
        return self.history["corner_displacement"]

    def __repr__(self):
        return (f"PlanResult({self.n_levels} levels, {self.n_steps} steps of {self.dt:.4g} s, "
                f"{self.n_impacts} impacts, peak base corner displacement "
                f"{self.peaks['base_corner_displacement']:.4g} m, peak rotation "
                f"{float(np.max(self.peaks['displacement'][:, 2])):.4g} rad, energy error "
                f"{self.energy['max_relative_error']:.2g})")


def _scene(scene, kind):
    if isinstance(scene, (str, os.PathLike)):
        scene = Scene.from_yaml(scene, kind)
    elif isinstance(scene, dict):
        scene = Scene.from_dict(scene, kind)
    if not isinstance(scene, Scene):
        raise TypeError(f"expected a kimp.Scene, a scene file or a dict, not {type(scene)}")
    if scene.kind != kind:
        scene = Scene(scene.text, scene.name, kind, directory=scene._base_directory())
    return scene


def _call(function, *args, file=None, **kwargs):
    """function(*args, **kwargs) with the engine's scene errors raised as SceneError (`file`:
    the name of the scene the messages start with)."""
    try:
        return function(*args, **kwargs)
    except (_kimp.SceneError, _kimp.UnitError) as error:
        raise SceneError(str(error), file) from None


def lumped(scene, case=None, records_dir=None):
    """Run a lumped scene as ``kimp lumped`` does (same engine, same numbers), in memory.

    scene: a kimp.Scene, a scene file path or a dict. case: run only the case of that name.
    records_dir: PEER records directory (like --records-dir). Returns the Result of the single
    case (a scene without `cases`, or `case` given), else Results (a list in case order with
    ``results["case"]`` and ``results.peaks``, {case: Peaks}); a scene with a `plan` section
    (pounding in plan) returns a PlanResult.
    """
    scene = _scene(scene, "lumped")
    if _kimp.has_plan(scene._parsed):
        if case is not None:
            raise ValueError("a scene in plan has no cases")
        return PlanResult(**_call(_kimp.run_plan, scene._parsed,
                                  os.fspath(records_dir) if records_dir else None,
                                  file=scene.name))
    cases = _call(_kimp.run_lumped, scene._parsed,
                  os.fspath(records_dir) if records_dir else None, case, file=scene.name)
    results = Results(_result(c) for c in cases)
    return results[0] if len(results) == 1 else results


@dataclass(repr=False)
class GroundMotion:
    """A ground acceleration record: samples at t_i = i·dt (dt in s, acceleration in m/s²)."""

    name: str
    dt: float
    acceleration: np.ndarray
    pga: float

    @property
    def time(self):
        """t_i = i·dt, s."""
        return np.arange(len(self.acceleration)) * self.dt

    @property
    def duration(self):
        """n·dt, s."""
        return len(self.acceleration) * self.dt

    def __repr__(self):
        return (f"GroundMotion({self.name!r}, {len(self.acceleration)} samples at {self.dt:g} s, "
                f"PGA {self.pga / 9.80665:.4g} g)")


def ground_motion(record="synthetic", *, scale_to_pga=None, scale=None, duration=None,
                  record_unit=None, records_dir=None, scene=None, **synthetic):
    """The ground motion of a scene's ``ground_motion`` section, as the CLI loads it.

    record: "synthetic" (the near-fault motion; its parameters as keywords, e.g. pga="0.5 g",
    pulse_period=1.2, seed=3), a PEER record name found in records_dir or a file path (AT2, or
    two columns "time acceleration" with record_unit, e.g. "g", "cm/s^2").
    scale_to_pga (m/s² or "0.4 g"), then scale (factor), then duration (s): trim.
    scene: take the section of a lumped kimp.Scene instead.
    """
    if scene is None:
        section = {"record": os.fspath(record)}
        for key, value in (("scale_to_pga", scale_to_pga), ("scale", scale),
                           ("duration", duration), ("record_unit", record_unit)):
            if value is not None:
                section[key] = value
        if synthetic:
            section["synthetic"] = synthetic
        scene = Scene.from_dict({"ground_motion": section}, "lumped", "<ground_motion>")
    scene = _scene(scene, "lumped")
    d = _call(_kimp.ground_motion, scene._parsed,
              os.fspath(records_dir) if records_dir else None, file=scene.name)
    return GroundMotion(**d)


@dataclass(repr=False)
class Collision:
    """A two-body collision (kimp collide's set-up): velocities after (m/s), effective COR,
    peak and minimum force (N), contact duration (s), max penetration (m), energies (J), and
    the contact-phase history: time (s), deformation δ (m), rate δ̇ (m/s), force (N)."""

    velocity_1_after: float
    velocity_2_after: float
    effective_cor: float
    peak_force: float
    min_force: float
    contact_duration: float
    max_penetration: float
    impact_velocity: float
    kinetic_energy_before: float
    kinetic_energy_loss: float
    dissipated_energy: float
    permanent_indentation: float
    momentum_error: float
    n_steps: int
    effective_mass: float
    time: np.ndarray
    deformation: np.ndarray
    rate: np.ndarray
    force: np.ndarray

    def __repr__(self):
        return (f"Collision(effective_cor={self.effective_cor:.4f}, peak_force="
                f"{self.peak_force:.4g} N, contact_duration={self.contact_duration:.4g} s, "
                f"max_penetration={self.max_penetration:.4g} m)")


def collide(law, *, mass_1=280e3, mass_2=300e3, velocity=1.0, velocity_2=0.0, time_step=2e-4,
            velocity_estimate="backward"):
    """Two free masses meeting through `law` (a kimp.laws object), central differences.

    mass_1, mass_2 in kg (or "280 t"), mass_2 = math.inf for a rigid wall (a text such as
    "inf t" is refused, as the scene of ``kimp collide`` refuses it: its masses are finite);
    velocity (m/s) of mass 1 towards mass 2 (velocity_2, m/s), time_step in s,
    velocity_estimate "backward" (the solver's) or "second_order". A law without m_eff gets
    m1·m2/(m1 + m2).
    """
    from .laws import _si

    if velocity_estimate not in ("backward", "second_order"):
        raise ValueError("velocity_estimate must be 'backward' or 'second_order'")
    m1 = _si(mass_1, "kg")
    m2 = math.inf if mass_2 == math.inf else _si(mass_2, "kg")
    m_eff = law.m_eff if law.m_eff else _kimp.effective_mass(m1, m2)
    d = _kimp.collide(law._make(m_eff), m1, m2,
                      _si(velocity, "m/s"), _si(velocity_2, "m/s"), _si(time_step, "s"),
                      velocity_estimate == "second_order")
    return Collision(**d)


@dataclass
class CorRow:
    """One row of the effective-COR table of ``kimp collide``: forces in N, duration in s,
    penetration in m, errors dimensionless."""

    name: str
    law: str
    nominal_cor: float
    effective_cor: float
    relative_error: float
    peak_force: float
    contact_duration: float
    max_penetration: float
    energy_error: float
    status: str


def cor_table(scene=None):
    """The effective-COR table of a collide scene (default: the thesis set-up), in memory."""
    scene = Scene.default("collide") if scene is None else _scene(scene, "collide")
    return [CorRow(**row) for row in _call(_kimp.cor_table, scene.text, scene.name,
                                           file=scene.name)]


@dataclass
class Parameter:
    """A fitted (or fixed) parameter with its confidence interval [lower, upper]."""

    value: float
    lower: float
    upper: float
    fitted: bool


@dataclass(repr=False)
class FitResult:
    """A fitted impact law, per metre of wall: stiffness k (N/m^n per m), cor, exponent n;
    normalised RMS misfits; FEM and model peak force (N/m), contact durations (s), impulses
    (N·s/m), contact start (s); the misfit window time (s), fem_force and model_force (N/m).
    ``peak_force_ratio``, ``impulse_ratio`` and ``contact_duration_ratio`` are fitted / FEM
    (1: the law reproduces the FEM impact exactly); a peak off by more than the fit's
    ``peak_tolerance`` (default 25 %) makes the verdict a warning.

    ``status`` is the optimiser's ("RelativeReductionTooSmall", ...); ``verdict`` is the fit's
    quality as ``kimp fit`` judges it (docs/physics.md §4 "Status of a fit"): "ok",
    "warning: <reason>" (e.g. a misfit window covering too little of the contact: k is then not
    reliable) or "failed: <reason>". ``ok`` is True for the verdict "ok"."""

    law: str
    stiffness: Parameter
    cor: Parameter
    exponent: Parameter
    normalised_rms: float
    normalised_displacement_rms: float
    function_evaluations: int
    status: str
    verdict: str
    fem_peak_force: float
    fem_contact_duration: float
    fem_impulse: float
    contact_start: float
    model_peak_force: float
    model_contact_duration: float
    model_impulse: float
    model_effective_cor: float
    peak_force_ratio: float
    impulse_ratio: float
    contact_duration_ratio: float
    time: np.ndarray
    fem_force: np.ndarray
    model_force: np.ndarray

    @property
    def ok(self):
        """True when the verdict is "ok" (neither a warning nor a failure)."""
        return self.verdict == "ok"

    @property
    def k(self):
        """The fitted k, N/m^n per metre of wall."""
        return self.stiffness.value

    def k_display(self, width=None):
        """k in kN/mm^n per metre (width None) or k·width in kN/mm^n (width in m)."""
        k = self.k * (width if width else 1.0)
        return k * 1e-3 ** (self.exponent.value + 1.0)

    def __repr__(self):
        unit = "kN/mm/m" if self.exponent.value == 1.0 else f"kN/mm^{self.exponent.value:g}/m"
        return (f"FitResult(law={self.law!r}, k={self.k_display():.5g} {unit}, "
                f"cor={self.cor.value:.4g}, n={self.exponent.value:g}, "
                f"normalised_rms={self.normalised_rms:.3g}, "
                f"peak_force_ratio={self.peak_force_ratio:.3g}, verdict={self.verdict!r})")


def _mass_per_metre(value, name):
    """kg per metre of wall from a number or a text of mass ("50 t", meant per metre) or of mass
    per length ("50 t/m")."""
    from .laws import _si

    if not isinstance(value, str):
        return float(value)
    try:
        return _si(value, "kg/m")
    except _kimp.UnitError as per_length:
        try:
            return _si(value, "kg")
        except _kimp.UnitError:
            raise _kimp.UnitError(f"{name}: {per_length}") from None


def fit(time, force, velocity, mass, law="kelvin_voigt", *, cor=_kimp.thesis_cor, exponent=None,
        fit_cor=False, fit_exponent=False, indentation=None, slab_displacement=None,
        displacement_weight=0.0, wall_mass=math.inf, force_only_contact=True,
        peak_tolerance=0.25):
    """Fit an impact law to a measured impact (fit::fit_impact_law, as ``kimp fit``).

    time (s), force (N per metre of wall, compressive > 0): arrays of one impact; velocity:
    impact velocity v_imp (m/s or a text: "1 m/s"); mass: slab mass (kg per metre of wall, or a
    text: "50 t/m", or "50 t" meaning per metre); wall_mass likewise (inf: a rigid wall). law:
    "kelvin_voigt", "jankowski", "hertzdamp" or "hysteretic", with `cor` fixed (or the start
    when fit_cor) and `exponent`. Optional indentation and slab_displacement (m) arrays as in
    the FEM results. The misfit window and separation settings are those of ``kimp fit`` and
    ``kimp study`` (one fitting configuration, docs/physics.md §4); as there,
    force_only_contact=True (the default) finds the contact from the force alone and ignores
    `indentation`. peak_tolerance: the largest relative miss of the FEM peak force by the
    fitted law's peak for an "ok" verdict (``fit.peak_tolerance``). Check the result's
    ``verdict`` and ``peak_force_ratio`` before using its k.
    """
    from .laws import _si

    if force_only_contact:
        indentation = None
    arrays = [None if a is None else np.asarray(a, float) for a in (indentation,
                                                                     slab_displacement)]
    d = _call(_kimp.fit, np.asarray(time, float), np.asarray(force, float),
              _si(velocity, "m/s"), _mass_per_metre(mass, "mass"), law, _si(cor, ""),
              _si(exponent, ""), fit_cor, fit_exponent, arrays[0], arrays[1],
              float(displacement_weight), _mass_per_metre(wall_mass, "wall_mass"),
              _si(peak_tolerance, ""))
    for key in ("stiffness", "cor", "exponent"):
        d[key] = Parameter(*d[key])
    return FitResult(**d)


def _need_fem():
    if not _kimp.with_fem:
        raise RuntimeError("kimp was built without the FEM engine (KIMP_WITH_FEM=OFF)")


def _run_into(run, scene, output, prefix, file):
    """run(text, name, directory, scene_directory) into `output` and kimp.read() of its `file`.
    Without `output` the run goes to a temporary directory, removed once the file is read (the
    returned ResultsFile holds every value in memory; its ``path`` is then None)."""
    if output is not None:
        output = os.fspath(output)
        os.makedirs(output, exist_ok=True)
        _call(run, scene.text, scene.name, output, scene._base_directory(), file=scene.name)
        return read(os.path.join(output, file))
    with tempfile.TemporaryDirectory(prefix=prefix) as work:
        _call(run, scene.text, scene.name, work, scene._base_directory(), file=scene.name)
        result = read(os.path.join(work, file))
    result.path = None
    return result


def fem(scene, output=None):
    """Run ``kimp fem`` on a FEM scene and return kimp.read() of its fem.h5. The command's files
    (fem.h5, summary.json, ...) are written to `output` and kept; without `output` they go to a
    temporary directory that is removed once fem.h5 is read. Needs a build with the FEM engine;
    MPI starts on first use (no mpirun needed)."""
    _need_fem()
    return _run_into(_kimp.run_fem, _scene(scene, "fem"), output, "kimp-fem-", "fem.h5")


def pushover(scene, output=None):
    """Run ``kimp fem --pushover`` on a FEM scene (section ``pushover``: displacement,
    unload_at, increment, cover, hinge_length) and return kimp.read() of its pushover.h5: per
    wall height /pushover/<case>/curve (displacement m, force N/m, segment, unloading) and
    /pushover/summary (capacity, initial, cracked and unloading stiffness, permanent set, ...).
    Files go to `output` (kept) or to a temporary directory. Needs the FEM engine."""
    _need_fem()
    return _run_into(_kimp.run_fem_pushover, _scene(scene, "fem"), output, "kimp-pushover-",
                     "pushover.h5")


def study(scene, output=None):
    """Run ``kimp study`` and return kimp.read() of its study.h5 (k table, fits, building
    response). The command's files (study.h5, k_table.csv, report.md, ...) are written to
    `output` and kept; without `output` they go to a temporary directory that is removed once
    study.h5 is read. Needs the FEM engine."""
    _need_fem()
    return _run_into(_kimp.run_study, _scene(scene, "study"), output, "kimp-study-", "study.h5")


__all__ = ["Peaks", "History", "Contact", "Wall", "Energy", "Result", "Results", "lumped", "GroundMotion",
           "ground_motion", "Collision", "collide", "CorRow", "cor_table", "Parameter",
           "FitResult", "fit", "fem", "pushover", "study"]
