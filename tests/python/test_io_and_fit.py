"""kimp.ground_motion, kimp.fit and kimp.read against the CLI: the motion a lumped run used, a
fitted law recovering the k that made its force history, and every command's results file read
back as the same numbers the API returns."""

import glob
import math
import os

import numpy as np
import pytest

import kimp
from conftest import QUICK_STUDY, SOURCE_DIR, run_cli

G = 9.80665


def test_synthetic_motion_scaling_and_trimming_are_the_scene_reader_s():
    base = kimp.ground_motion(pga="0.5 g", seed=3)
    assert base.pga == 0.5 * G
    assert base.dt == 0.005 and base.duration == pytest.approx(20.0)
    flipped = kimp.ground_motion(pga="0.5 g", seed=3, scale=-2.0)
    np.testing.assert_array_equal(flipped.acceleration, -2.0 * base.acceleration)
    short = kimp.ground_motion(pga="0.5 g", seed=3, duration="4 s")
    np.testing.assert_array_equal(short.acceleration, base.acceleration[:800])
    assert kimp.ground_motion(pga="0.5 g", scale_to_pga="0.3 g").pga == pytest.approx(0.3 * G,
                                                                                      rel=1e-15)
    with pytest.raises(kimp.SceneError, match="unknown key 'nope' in ground_motion.synthetic"):
        kimp.ground_motion(nope=1.0)


def test_ground_motion_of_a_scene_is_the_one_the_cli_run_used(tmp_path):
    scene = kimp.Scene.from_dict({"ground_motion": {"record": "synthetic", "scale_to_pga": "0.4 g",
                                                    "scale": 1.5, "duration": "2 s"}})
    path = tmp_path / "scene.yaml"
    scene.write(path)
    run_cli("lumped", path, "-o", tmp_path / "out")
    cli = kimp.read(tmp_path / "out" / "lumped.h5")
    motion = kimp.ground_motion(scene=scene)
    assert motion.pga == cli["lumped/default/pga"]
    assert len(motion.acceleration) == 400


def test_at2_record_as_the_cli_reads_it(tmp_path):
    records = os.environ.get("KIMP_RECORDS_DIR", os.path.join(SOURCE_DIR, "..", "shared", "data",
                                                               "records"))
    files = sorted(glob.glob(os.path.join(records, "RSN*.AT2")))
    if not files:
        pytest.skip(f"no PEER records in {records}")
    motion = kimp.ground_motion(files[0], duration="5 s")
    scene = kimp.Scene.from_dict({"ground_motion": {"record": files[0], "duration": "5 s"},
                                  "integration": {"output_interval": "0.1 s"}})
    scene.write(tmp_path / "scene.yaml")
    run_cli("lumped", tmp_path / "scene.yaml", "-o", tmp_path / "out")
    assert motion.pga == kimp.read(tmp_path / "out" / "lumped.h5")["lumped/default/pga"]
    assert motion.name in files[0]


def test_fit_recovers_the_kelvin_voigt_stiffness_of_a_collision():
    # A 50 t/m slab at 1 m/s on a rigid wall through Kelvin-Voigt (k = 400 kN/mm/m, COR 0.7):
    # the fitter, which models the same set-up, finds k back to the discretisation error of the
    # 1e-5 s record (measured: 1.3e-4 relative).
    k, mass, v, dt = 4e8, 50e3, 1.0, 1e-5
    hit = kimp.collide(kimp.laws.KelvinVoigt(k=k, cor=0.7), mass_1=mass, mass_2=math.inf,
                       velocity=v, time_step=dt)
    # Start the record before the contact, at the same sampling, as a measured record does.
    time = np.concatenate([[-2 * dt, -dt, 0.0], hit.time])
    force = np.concatenate([[0.0, 0.0, 0.0], hit.force])
    result = kimp.fit(time, force, velocity=v, mass=mass, law="kelvin_voigt", cor=0.7)
    assert result.k == pytest.approx(k, rel=1e-3)
    assert result.cor.value == 0.7 and not result.cor.fitted
    assert result.normalised_rms < 0.05
    assert "kN/mm/m" in repr(result)
    assert result.k_display() == pytest.approx(400, rel=1e-3)


def test_fit_reports_how_well_it_reproduces_the_peak_and_warns_when_it_misses_it():
    # A sharp spike on a long, low pulse: Kelvin-Voigt fitted to the whole pulse cuts the spike.
    time = np.arange(-50, 1501) * 2e-5
    duration, rise = 0.02, 0.02 / 40
    inside = (time > 0) & (time < duration)
    force = np.where(inside, 1.37e6 * (0.3 * np.sin(np.pi * time / duration)
                                       + 0.7 * (time / rise) * np.exp(1 - time / rise)), 0.0)
    result = kimp.fit(time, force, velocity=1.0, mass=3840.0, law="kelvin_voigt", cor=0.7)
    assert result.peak_force_ratio == pytest.approx(result.model_peak_force
                                                    / result.fem_peak_force)
    assert result.peak_force_ratio < 0.75
    assert result.verdict.startswith("warning: ") and "fitted peak force" in result.verdict
    assert not result.ok
    assert math.isfinite(result.impulse_ratio) and math.isfinite(result.contact_duration_ratio)
    assert "peak_force_ratio=" in repr(result)
    loose = kimp.fit(time, force, velocity=1.0, mass=3840.0, law="kelvin_voigt", cor=0.7,
                     peak_tolerance=1.0 - result.peak_force_ratio + 0.01)
    assert "peak force" not in loose.verdict
    with pytest.raises(ValueError):
        kimp.fit(time, force, velocity=1.0, mass=3840.0, peak_tolerance=0.0)


def test_a_kimp_fit_directory_is_a_k_table_of_a_scene(tmp_path):
    # The fit_table.csv of `kimp fit` (its directory) as impact.k_table: k_total of the
    # Kelvin-Voigt fit at COR 0.7, linear in the wall height.
    fit = tmp_path / "fit"
    fit.mkdir()
    (fit / "fit_table.csv").write_text(
        "case,wall_height_m,impact_velocity_m_per_s,variant,law,k_total,status\n"
        "H1.00,1,1,kelvin_voigt_cor_fixed,kelvin_voigt,4000,ok\n"
        "H1.00,1,1,jankowski_cor_fixed,jankowski,2000,ok\n"
        "H2.00,2,1,kelvin_voigt_cor_fixed,kelvin_voigt,2000,ok\n"
        "H2.00,2,1,jankowski_cor_fixed,jankowski,1000,ok\n")
    (tmp_path / "scene.yaml").write_text(
        'building:\n  n_storeys: 3\nwalls:\n  left:\n    gap: "2 cm"\n  right:\n'
        '    gap: "2 cm"\nimpact:\n  law: kelvin_voigt\n  k_table: fit\n'
        '  wall_height: "1.5 m"\nground_motion:\n  record: synthetic\n  duration: "6 s"\n')
    scene = kimp.Scene.from_yaml(tmp_path / "scene.yaml")
    result = kimp.lumped(scene)
    assert result.status == "ok"
    # The same run with k given by hand: (4000 + 2000)/2 kN/mm at H = 1.5 m.
    by_hand = kimp.lumped(scene.with_(**{"impact.k_table": "", "impact.k": "3000 kN/mm"}))
    peak = max(c.peak_force for c in result.contacts)
    assert peak > 0
    assert peak == pytest.approx(max(c.peak_force for c in by_hand.contacts), rel=1e-12)


def test_read_round_trips_a_sweep(tmp_path):
    run_cli("sweep", "data/studies/quick_gap_sweep.yaml", "-o", tmp_path / "out")
    sweep = kimp.read(tmp_path / "out" / "sweep.h5")["sweep"]
    gaps = sweep["parameters_si"]["walls.left.gap, walls.right.gap"]
    cors = sweep["parameters_si"]["impact.cor"]
    scene = kimp.Scene.from_yaml(os.path.join(SOURCE_DIR, "data/studies/scenes/quick_scene.yaml"))
    for i in (0, len(gaps) - 1):
        r = kimp.lumped(scene.with_(**{"walls.left.gap": float(gaps[i]),
                                       "walls.right.gap": float(gaps[i]),
                                       "impact.cor": float(cors[i])}))
        for dof in range(5):
            assert r.peaks.displacement[dof] == sweep["metrics"][f"peak_displacement_dof{dof}"][i]
        assert r.n_impacts == sweep["metrics"]["n_impacts"][i]


@pytest.mark.skipif(not kimp.with_fem, reason="built without the FEM engine")
def test_fem_and_fit_round_trip_against_the_cli(tmp_path):
    scene = os.path.join(SOURCE_DIR, "data/scenes/fem_quick.yaml")
    fem = kimp.fem(scene, tmp_path / "api")
    run_cli("fem", scene, "-o", tmp_path / "cli")
    cli = kimp.read(tmp_path / "cli" / "fem.h5")
    for name, case in cli["fem"].items():
        mine = fem["fem"][name]
        assert mine.status == case.status == "ok"
        np.testing.assert_array_equal(mine["contact_force"].value, case["contact_force"].value)
        assert case["contact_force"].units == "N/m"
    # `kimp fit` of that file against kimp.fit of the same history: every variant of the CLI
    # (law, COR fixed or free, free exponent), its k, COR, n, misfit, model force and verdict.
    run_cli("fit", tmp_path / "cli" / "fem.h5", "-o", tmp_path / "fit")
    fitted = kimp.read(tmp_path / "fit" / "fit.h5")
    name, case = next(iter(cli["fem"].items()))
    series = case["smoothed_contact_force"]
    variants = {"kelvin_voigt_cor_fixed": ("kelvin_voigt", False, False),
                "jankowski_cor_fixed": ("jankowski", False, False),
                "kelvin_voigt_cor_free": ("kelvin_voigt", True, False),
                "jankowski_cor_free": ("jankowski", True, False),
                "hertz_free_exponent": ("hysteretic", False, True)}
    assert sorted(v for v in fitted["fit"][name].keys() if v in variants) == sorted(variants)
    for variant, (law, fit_cor, fit_exponent) in variants.items():
        mine = kimp.fit(series.time, series.value, velocity=case["impact_velocity"],
                        mass=case["slab_mass"], law=law, cor=0.7, fit_cor=fit_cor,
                        fit_exponent=fit_exponent, indentation=case["indentation"].value,
                        slab_displacement=case["slab_displacement"].value)
        group = fitted["fit"][name][variant]
        assert group.attrs["law"] == law, variant
        assert mine.k == group["stiffness"], variant
        assert mine.cor.value == group["cor"] and mine.exponent.value == group["exponent"]
        assert mine.normalised_rms == group["normalised_rms"], variant
        np.testing.assert_array_equal(mine.model_force, group["model_force"].value,
                                      err_msg=variant)
        np.testing.assert_array_equal(mine.time, group["model_force"].time, err_msg=variant)
        np.testing.assert_array_equal(mine.fem_force, group["fem_force"].value, err_msg=variant)
        assert mine.verdict == group.attrs["status"], variant
        assert mine.peak_force_ratio == group["peak_force_ratio"], variant
        assert mine.impulse_ratio == group["impulse_ratio"], variant
        assert mine.status == group.attrs["lm_status"], variant
    # The CLI's slab mass is stored per metre of wall with its unit: as a text it reads the same.
    assert case["slab_mass"].units == "kg/m"
    again = kimp.fit(series.time, series.value, velocity=f"{float(case['impact_velocity'])!r} m/s",
                     mass=f"{float(case['slab_mass'])!r} kg/m")
    assert again.k == fitted["fit"][name]["kelvin_voigt_cor_fixed"]["stiffness"]


@pytest.mark.skipif(not kimp.with_fem, reason="built without the FEM engine")
def test_study_round_trips_against_the_cli(tmp_path):
    path = tmp_path / "study.yaml"
    path.write_text(QUICK_STUDY)
    mine = kimp.study(kimp.Scene.from_yaml(path, kind="study"), tmp_path / "api")
    run_cli("study", path, "-o", tmp_path / "cli")
    cli = kimp.read(tmp_path / "cli" / "study.h5")
    assert mine.scene == cli.scene == QUICK_STUDY
    fitted = [(name, group) for name, group in cli["fit"].items()]
    assert fitted
    for name, group in fitted:
        laws = [v for v, result in group.items() if isinstance(result, kimp.Group)]
        assert laws, name
        for law in laws:
            assert mine["fit"][name][law]["stiffness"] == group[law]["stiffness"], (name, law)
            np.testing.assert_array_equal(mine["fit"][name][law]["model_force"],
                                          group[law]["model_force"])


def test_fit_and_collide_take_unit_texts_like_the_other_functions():
    k, mass, v, dt = 4e8, 50e3, 1.0, 1e-5
    hit = kimp.collide(kimp.laws.KelvinVoigt(k=k, cor=0.7), mass_1="50 t", mass_2=math.inf,
                       velocity="1 m/s", time_step="0.01 ms")
    same = kimp.collide(kimp.laws.KelvinVoigt(k=k, cor=0.7), mass_1=mass, mass_2=math.inf,
                        velocity=v, time_step=dt)
    np.testing.assert_array_equal(hit.force, same.force)
    time = np.concatenate([[-2 * dt, -dt, 0.0], hit.time])
    force = np.concatenate([[0.0, 0.0, 0.0], hit.force])
    in_si = kimp.fit(time, force, velocity=v, mass=mass)
    # "50 t" is read per metre of wall, like "50 t/m"; the results are the same bits.
    for texts in ({"velocity": "1 m/s", "mass": "50 t"}, {"velocity": "100 cm/s", "mass": "50 t/m"},
                  {"velocity": v, "mass": "50000 kg/m", "wall_mass": "1e12 t"}):
        fitted = kimp.fit(time, force, **texts)
        if "wall_mass" in texts:
            # A 1e12 t/m wall: m_eff within 5e-14 of the slab's, k within the fit's tolerance.
            assert fitted.k == pytest.approx(in_si.k, rel=1e-6)
            continue
        assert fitted.k == in_si.k, texts
        np.testing.assert_array_equal(fitted.model_force, in_si.model_force)
    with pytest.raises(ValueError, match="expected a mass"):
        kimp.fit(time, force, velocity=v, mass="50 m")
    # The CLI's scenes hold finite masses: "inf" is refused as `kimp collide` refuses it, a
    # rigid wall is the float math.inf.
    with pytest.raises(ValueError, match="'inf' is not a finite number"):
        kimp.collide(kimp.laws.KelvinVoigt(k=k, cor=0.7), mass_1="50 t", mass_2="inf")
    assert hit.effective_mass == mass
