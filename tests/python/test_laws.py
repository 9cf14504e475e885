"""kimp.laws against the closed forms of docs/physics.md §1 (those of the C++ closed-form tests)
and kimp.collide / kimp.cor_table against `kimp collide`."""

import math

import numpy as np
import pytest

import kimp
from conftest import run_cli

K_LINEAR = 2.5e9                  # 2500 kN/mm, N/m
K_HERTZ = 2.3717e10               # 750 kN/mm^1.5, N/m^1.5
M_EFF = 280e3 * 300e3 / 580e3     # kg
ROUND_OFF = 1e-12                 # relative: the formulas are evaluated the same way


def kv_damping_ratio(cor):
    return -math.log(cor) / math.sqrt(math.pi ** 2 + math.log(cor) ** 2)


def test_kelvin_voigt_is_k_delta_plus_c_delta_dot_with_c_from_the_cor():
    law = kimp.laws.KelvinVoigt(k="2500 kN/mm", cor=0.7, m_eff=M_EFF)
    assert law.k == K_LINEAR
    assert kv_damping_ratio(0.7) == pytest.approx(0.1128084507, abs=1e-10)
    c = 2.0 * kv_damping_ratio(0.7) * math.sqrt(K_LINEAR * M_EFF)
    delta = np.linspace(1e-4, 2e-2, 50)
    rate = np.linspace(0.1, 1.5, 50)
    np.testing.assert_allclose(law.force(delta, rate), K_LINEAR * delta + c * rate,
                               rtol=ROUND_OFF)
    np.testing.assert_allclose(law.damping(delta, rate), c, rtol=ROUND_OFF)
    np.testing.assert_allclose(law.stiffness(delta, rate), K_LINEAR, rtol=ROUND_OFF)
    # Broadcasting like any numpy function; open gap: no force.
    assert law.force(delta[:, None], rate[None, :]).shape == (50, 50)
    assert law.force(-1e-3, 1.0) == 0.0


def test_linear_and_jankowski_closed_forms():
    delta = np.linspace(1e-4, 1e-2, 20)
    np.testing.assert_allclose(kimp.laws.Linear(K_LINEAR).force(delta, 0.3), K_LINEAR * delta,
                               rtol=ROUND_OFF)
    cor = 0.7
    xi = 9 * math.sqrt(5) / 2 * (1 - cor ** 2) / (cor * (cor * (9 * math.pi - 16) + 16))
    assert xi == pytest.approx(0.2981090815, abs=1e-10)
    law = kimp.laws.Jankowski(k="750 kN/mm^1.5", cor=cor, m_eff=M_EFF)
    assert law.k == pytest.approx(K_HERTZ, rel=1e-4)
    c = 2 * xi * np.sqrt(law.k * np.sqrt(delta) * M_EFF)
    np.testing.assert_allclose(law.force(delta, 0.8), law.k * delta ** 1.5 + c * 0.8,
                               rtol=1e-12)
    # Restoring (δ̇ < 0) along a path: the dashpot is off.
    path = law.path([1e-3, 2e-3, 1.5e-3], [0.5, 0.5, -0.5])
    assert path[2] == pytest.approx(law.k * 1.5e-3 ** 1.5, rel=1e-12)


def test_hertzdamp_at_first_contact_uses_the_rate_as_impact_velocity():
    law = kimp.laws.Hertzdamp(k=K_HERTZ, cor=0.6)
    beta = 3 * (1 - 0.6 ** 2) / 4
    delta = np.array([1e-3, 4e-3])
    np.testing.assert_allclose(law.force(delta, 1.0), K_HERTZ * delta ** 1.5 * (1 + beta),
                               rtol=1e-12)


def test_every_law_is_available_by_its_scene_name():
    params = {"linear": {"k": K_LINEAR}, "hertzdamp": {"k": K_HERTZ}}
    for name in kimp.laws.names():
        kw = params.get(name, {"k": K_HERTZ if name != "kelvin_voigt" and
                               name != "modified_kelvin_voigt" else K_LINEAR, "m_eff": M_EFF})
        if name == "bumper":
            kw = {"k": "0.36 kN/mm^2.65", "m_eff": M_EFF}
        law = kimp.laws.make(name, **kw)
        assert law.force(1e-3, 0.5) > 0.0, name
        assert law.law == name and repr(law).startswith(type(law).__name__ + "(k=")
    with pytest.raises(ValueError, match="unknown law"):
        kimp.laws.make("nope", k=1.0)


def test_the_law_classes_are_made_from_the_traits_alone():
    # Every law of the C++ traits (lumped/laws/law_traits.h) is a class of kimp.laws with the
    # traits' name, keyword arguments and defaults: a new law needs no edit of the package.
    import inspect
    traits = kimp._kimp.law_traits()
    assert [t["name"] for t in traits] == kimp.laws.names()
    assert [t["number"] for t in traits] == list(range(1, len(traits) + 1))
    for t in traits:
        cls = getattr(kimp.laws, t["class_name"])
        assert cls.law == t["name"] and t["class_name"] in kimp.laws.__all__
        assert kimp.laws.make(t["name"], k=1e9).__class__ is cls
        parameters = list(inspect.signature(cls.__init__).parameters.values())[1:]
        assert [p.name for p in parameters] == [p[0] for p in t["parameters"]]
        for p, (name, _unit, required, default) in zip(parameters, t["parameters"]):
            assert (p.default is inspect.Parameter.empty) == required, name
            if not required:
                assert p.default == default, name
        law = cls(1e9)
        assert law.exponent == t["default_exponent"]
        assert ("cor" in [p.name for p in parameters]) == t["uses_cor"]
        if t["uses_cor"]:
            assert law.cor == kimp.thesis_cor == 0.7
        with pytest.raises(TypeError):
            cls(1e9, no_such_parameter=1.0)


def test_collide_matches_the_cli_cor_table(tmp_path):
    run_cli("collide", "-o", tmp_path / "out")
    cli = kimp.read(tmp_path / "out" / "collide.h5")
    table = kimp.cor_table()
    names = [g for g in cli.keys() if g not in ("meta", "input")]
    assert names, cli
    rows = {(r.name, r.nominal_cor): r for r in table}
    # The thesis set-up: Kelvin-Voigt at COR 0.7 from collide() equals its row of the table.
    kv = kimp.collide(kimp.laws.KelvinVoigt(k="2500 kN/mm", cor=0.7), mass_1="280 t",
                      mass_2="300 t", velocity=1.0, time_step=2e-4)
    row = [r for r in table if r.law == "kelvin_voigt" and r.nominal_cor == 0.7][0]
    assert kv.effective_cor == row.effective_cor
    assert kv.peak_force == row.peak_force
    assert kv.effective_mass == pytest.approx(M_EFF, rel=1e-15)
    assert kv.force.shape == kv.time.shape and kv.force.max() == kv.peak_force
    # Against the CLI's collide.h5 (/collide/<law>/cor_table): every column, row by row.
    for name, group in cli["collide"].items():
        mine = [r for r in table if r.name == name]
        assert len(mine) == len(group["cor_table"]["nominal_cor"]) > 0, name
        for column in ("nominal_cor", "effective_cor", "peak_force", "contact_duration",
                       "max_penetration", "energy_error"):
            np.testing.assert_array_equal(group["cor_table"][column],
                                          [getattr(r, column) for r in mine], err_msg=name)
    assert len(rows) == len(table)


def impact_damping_coefficient(cor, m_eff, v_imp):
    """C_imp of eq. 2.23 (docs/physics.md §1): 1.55(1 − e²)/(e^0.7076 · m_eff^0.0025 · v^0.9755),
    m_eff in kg, v_imp in m/s."""
    return 1.55 * (1 - cor ** 2) / (cor ** 0.7076 * m_eff ** 0.0025 * v_imp ** 0.9755)


def test_modified_kelvin_voigt_keeps_the_remaining_deformation_as_permanent_set():
    law = kimp.laws.ModifiedKelvinVoigt(k=K_LINEAR, cor=0.5, m_eff=M_EFF)
    c = 2.0 * kv_damping_ratio(0.5) * math.sqrt(K_LINEAR * M_EFF)
    # Open at −5 mm, in to 5 mm at 1 m/s, turn (δ̇ = 0), then at 2 mm opening at 1 m/s, where
    # k·δ + c·δ̇ < 0: the contact ends there and δ_p = 2 mm stays. Then 1.5 mm (inside the set:
    # no force) and 3 mm closing at 0.5 m/s: F = k·(δ − δ_p) + c·δ̇.
    assert K_LINEAR * 2e-3 - c < 0.0
    force = law.path([-5e-3, 5e-3, 5e-3, 2e-3, 1.5e-3, 3e-3], [1.0, 1.0, 0.0, -1.0, 0.5, 0.5])
    assert force[1] == pytest.approx(K_LINEAR * 5e-3 + c, rel=ROUND_OFF)
    assert force[2] == pytest.approx(K_LINEAR * 5e-3, rel=ROUND_OFF)
    assert force[3] == 0.0 and force[4] == 0.0
    assert force[5] == pytest.approx(K_LINEAR * 1e-3 + c * 0.5, rel=ROUND_OFF)
    # Kelvin-Voigt (law 2) at the same point pulls: k·δ + c·δ̇ < 0, the tension law 3 removes.
    kv = kimp.laws.KelvinVoigt(k=K_LINEAR, cor=0.5, m_eff=M_EFF)
    assert kv.path([-5e-3, 5e-3, 5e-3, 2e-3], [1.0, 1.0, 0.0, -1.0])[3] == pytest.approx(
        K_LINEAR * 2e-3 - c, rel=ROUND_OFF)
    # In a collision the permanent set is what kimp.collide reports: a second law object ends
    # its contact where k·δ + c·δ̇ turns negative, above zero indentation.
    hit = kimp.collide(law, mass_1="280 t", mass_2="300 t", velocity=1.0, time_step=2e-5)
    assert hit.permanent_indentation > 0.0 and hit.min_force >= 0.0


def test_hysteretic_restitution_is_reduced_by_c_imp_and_clipped_at_zero():
    law = kimp.laws.Hysteretic(k=K_HERTZ, cor=0.7, m_eff=M_EFF)
    c_imp = impact_damping_coefficient(0.7, M_EFF, 1.0)
    # The C++ test's independent evaluation of eq. 2.23 at the thesis m_eff and 1 m/s.
    assert c_imp == pytest.approx(0.98766206409, abs=1e-10)
    spring = K_HERTZ * 4e-3 ** 1.5
    # Approach at v_imp = 1 m/s to 5 mm: the Hertz spring alone; restitution at 4 mm opening at
    # 0.3 m/s: spring·(1 + C_imp·δ̇); opening faster than 1/C_imp: no force (no tension).
    approach = law.path([-5e-3, 5e-3], [1.0, 1.0])
    assert approach[1] == pytest.approx(K_HERTZ * 5e-3 ** 1.5, rel=ROUND_OFF)
    back = law.path([-5e-3, 5e-3, 4e-3], [1.0, 1.0, -0.3])
    assert back[2] == pytest.approx(spring * (1.0 - 0.3 * c_imp), rel=ROUND_OFF)
    assert law.path([-5e-3, 5e-3, 4e-3], [1.0, 1.0, -1.1 / c_imp])[2] == 0.0
    # A faster impact: C_imp (s/m) falls as v_imp^−0.9755 and multiplies the rate itself.
    c_2 = impact_damping_coefficient(0.7, M_EFF, 2.0)
    assert law.path([-5e-3, 5e-3, 4e-3], [2.0, 2.0, -0.6])[2] == pytest.approx(
        spring * (1.0 - 0.3 * c_2 * 2.0), rel=ROUND_OFF)


def test_hysteretic_with_a1_uses_a1_times_one_minus_e_squared_and_its_loop_area():
    # C_imp = a1·(1 − e²). Quasi-static loop, load at +r to δ_m, unload at −r: the area is
    # C·r·k·δ_m^(n+1)/(n+1) (C·r < 1), here integrated from the path by the trapezoidal rule
    # over 20,000 samples a leg: O(1/n) from the rate's jump at the turn, < 1e-3 relative.
    a1, cor, r, delta_m, n = 0.8, 0.6, 0.5, 8e-3, 20000
    law = kimp.laws.Hysteretic(k=K_HERTZ, cor=cor, m_eff=M_EFF, a1=a1)
    c = a1 * (1 - cor ** 2)
    up = delta_m * np.arange(n + 1) / n
    delta = np.concatenate([up, up[-2::-1]])
    rate = np.concatenate([np.full(n, r), [0.0], np.full(n, -r)])
    force = law.path(delta, rate)
    # Unloading: F = k·δ^n·(1 − C·r), C = a1·(1 − e²) whatever m_eff and v_imp.
    assert force[n + 1] == pytest.approx(K_HERTZ * up[-2] ** 1.5 * (1 - c * r), rel=ROUND_OFF)
    area = np.trapz(force, delta)  # ∮F dδ: loading minus unloading work
    expected = c * r * K_HERTZ * delta_m ** 2.5 / 2.5
    assert area == pytest.approx(expected, rel=1e-3)
    assert "a1=0.8" in repr(law) and "a1 in s/m" in repr(law)


def test_hertzdamp_ye_damping_factor_and_the_rate_over_v_imp():
    md = kimp.laws.Hertzdamp(k=K_HERTZ, cor=0.6)
    ye = kimp.laws.Hertzdamp(k=K_HERTZ, cor=0.6, ye=True)
    beta_md = 0.75 * (1 - 0.6 ** 2)
    beta_ye = 8 * (1 - 0.6) / (5 * 0.6)
    hertz = K_HERTZ * 1e-3 ** 1.5
    # First contact at δ̇ = v_imp: F = k·δ^n·(1 + β).
    assert md.force(1e-3, 1.0) == pytest.approx(hertz * (1 + beta_md), rel=ROUND_OFF)
    assert ye.force(1e-3, 1.0) == pytest.approx(hertz * (1 + beta_ye), rel=ROUND_OFF)
    # Later in the contact (v_imp = 2 m/s): F = k·δ^n·(1 + β·δ̇/v_imp).
    force = ye.path([-5e-3, 5e-3, 4e-3], [2.0, 2.0, 1.0])
    assert force[2] == pytest.approx(K_HERTZ * 4e-3 ** 1.5 * (1 + beta_ye * 0.5), rel=ROUND_OFF)
    # Hertzdamp has no m_eff: its repr says so.
    assert "m_eff" not in repr(ye) and "ye=True" in repr(ye) and "[k in N/m^1.5]" in repr(ye)


def test_bumper_hands_over_to_the_wall_beyond_the_ultimate_deformation():
    # k_b of four 150 × 150 × 50 mm bumpers, K_r = 55835 kN/m², n = 2.65 (thesis eqs. 6.2-6.3).
    k_b = 2.25 * 4 * 0.15 * 0.15 * 55835e3 / 0.05 ** 2.65
    delta_u, k_w = 0.0375, 1.5e9
    law = kimp.laws.Bumper(k=k_b, cor=0.7, m_eff=M_EFF, delta_u=delta_u, k_w=k_w)
    f_u = k_b * delta_u ** 2.65

    def loading(delta):
        """F on loading at 0.5 m/s after an impact at 1 m/s to 1 cm."""
        return law.path([-5e-3, 0.01, delta], [1.0, 1.0, 0.5])[2]

    # Continuous at δ_u (the rubber's k_b·δ_u^n on both sides), then the wall's k_w on top.
    assert loading(delta_u * (1 - 1e-12)) == pytest.approx(f_u, rel=1e-9)
    assert loading(delta_u * (1 + 1e-12)) == pytest.approx(f_u, rel=1e-9)
    assert loading(0.04) == pytest.approx(f_u + k_w * (0.04 - delta_u), rel=ROUND_OFF)
    assert loading(0.02) == pytest.approx(k_b * 0.02 ** 2.65, rel=ROUND_OFF)
    assert law.stiffness(0.04, 0.5) == k_w
    assert law.stability_stiffness(0.05) == max(2.65 * k_b * delta_u ** 1.65, k_w)
    assert "delta_u in m" in repr(law) and "k_w in N/m" in repr(law)
