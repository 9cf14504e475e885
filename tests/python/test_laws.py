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
