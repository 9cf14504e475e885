"""kimp.fem and kimp.study (FEM build): the GIL released while they run, their temporary
directories removed, the paths of a scene file relative to it."""

import os
import tempfile
import time

import numpy as np
import pytest

import kimp
from conftest import QUICK_STUDY, SOURCE_DIR, run_beside_a_python_thread

pytestmark = pytest.mark.skipif(not kimp.with_fem, reason="built without the FEM engine")

FEM_QUICK = os.path.join(SOURCE_DIR, "data/scenes/fem_quick.yaml")


def check_runs_beside_python(run):
    """`run` (a FEM run) does not stop another Python thread: that thread's longest pause is
    well below the run's own duration (measured alone first, which also starts MPI)."""
    start = time.perf_counter()
    expected = run()
    alone = time.perf_counter() - start
    assert alone > 0.1, "the run must be long enough to observe"
    result, longest_pause, ticks = run_beside_a_python_thread(run)
    assert longest_pause < 0.5 * alone, (longest_pause, alone, ticks)
    assert ticks > 1000
    return expected, result


def test_fem_releases_the_gil():
    expected, result = check_runs_beside_python(lambda: kimp.fem(FEM_QUICK))
    name = next(iter(expected["fem"].keys()))
    np.testing.assert_array_equal(result["fem"][name]["contact_force"].value,
                                  expected["fem"][name]["contact_force"].value)


def test_study_releases_the_gil(tmp_path):
    scene = kimp.Scene.from_dict(kimp.Scene(QUICK_STUDY, kind="study").to_dict(), kind="study")
    expected, result = check_runs_beside_python(lambda: kimp.study(scene))
    assert float(result["k_table"]["kelvin_voigt"][0]) == float(
        expected["k_table"]["kelvin_voigt"][0])


def test_temporary_directories_are_removed_and_given_ones_kept(tmp_path, monkeypatch):
    # Every temporary directory of this test goes below tmp_path/tmp (not the shared /tmp).
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(scratch))
    fem = kimp.fem(FEM_QUICK)
    study = kimp.study(kimp.Scene(QUICK_STUDY, kind="study"))
    assert list(scratch.iterdir()) == []
    # What was read stays: every value is in memory, the file is gone (path None).
    assert fem.path is None and study.path is None
    assert len(next(iter(fem["fem"].values()))["contact_force"].value) > 100
    assert float(study["k_table"]["kelvin_voigt"][0]) > 0.0
    # A directory the user names keeps the command's files.
    kept = kimp.study(kimp.Scene(QUICK_STUDY, kind="study"), tmp_path / "kept")
    assert kept.path == str(tmp_path / "kept" / "study.h5")
    assert {"study.h5", "k_table.csv", "report.md"} <= set(os.listdir(tmp_path / "kept"))
    # A run that fails leaves nothing behind either.
    with pytest.raises(Exception):
        kimp.fem(kimp.Scene("wall_heights: []\n", kind="fem"))
    assert list(scratch.iterdir()) == []


def test_the_site_study_fits_with_no_verdict_but_the_peak_warning():
    # The site study's k comes from fits that pass kimp fit's checks (the rigid-slab quick
    # scene's chattering contact would not: its misfit window covers ~2 % of the contact).
    study = kimp.study(kimp.Scene(QUICK_STUDY, kind="study"))
    # Their one warning, if any, is the honest one: the least-squares fit reproduces the pulse,
    # and its peak is below the FEM's first (wave) peak by more than the peak tolerance.
    for law in ("kelvin_voigt", "jankowski"):
        status = study[f"fit/H1.25/{law}"].status
        assert status == "ok" or (status.startswith("warning: the fitted peak force is")
                                  and ";" not in status), status
    # On the 5 cm contact mesh k_KV is 92.9 kN/mm/m, 3 % above the thesis' 90 (Table 2.1);
    # the 2.5 cm mesh gives 89.9 (the notebook's ladder).
    table = study["k_table"]
    assert float(table["kelvin_voigt"][0]) == pytest.approx(90.0, rel=0.05)
    assert float(table["thesis_kelvin_voigt"][0]) == 90.0


PUSHOVER_SCENE = """
wall_heights: ["1.25 m"]
mesh: {h_contact: "10 cm", h_max: "40 cm", grading: 1.3}
geometry: {backfill_width: "4 m"}
interface: {model: contact}
materials:
  soil: {model: mohr_coulomb, phi: 30, c: "1 kPa", psi: 0, tension_cutoff: "1 kPa"}
pushover: {displacement: "12 mm", unload_at: ["6 mm"], increment: "2 mm"}
"""


def test_pushover_writes_the_curve_and_its_summary(tmp_path):
    result = kimp.pushover(kimp.Scene(PUSHOVER_SCENE, kind="fem"), tmp_path / "out")
    curve = result["pushover"]["H1.25"]["curve"]
    force = np.asarray(curve["force"])
    displacement = np.asarray(curve["displacement"])
    assert displacement.max() == pytest.approx(0.012)
    # A wall pushed into sand resists: the force grows on the first push, and the unloading
    # reached zero force at a permanent set below 6 mm.
    summary = result["pushover"]["summary"]
    assert float(summary["capacity"][0]) > 10e3
    assert 0 < float(summary["permanent_set"][0]) < 0.006
    with open(tmp_path / "out" / "pushover.csv") as f:
        header = f.readline().strip().split(",")
    assert header[:4] == ["case", "wall_height_m", "displacement_m", "force_N_per_m"]
    assert (tmp_path / "out" / "pushover_summary.csv").exists()
    assert len(force) == len(displacement)


def test_study_yielding_wall_keys_through_the_scene_builder(tmp_path):
    # The keys an inelastic study's yielding wall element reads, set as SI numbers through the
    # scene builder: the materials that make the study inelastic, the interface, the pushover's
    # path (its cyclic unloading gives k_ur), the building's mass and width.
    scene = kimp.Scene(QUICK_STUDY, kind="study").with_(**{
        "fem.slab.rigid": True,
        "fem.interface.model": "contact",
        "fem.materials.concrete.model": "elastic",
        "fem.materials.soil.model": "mohr_coulomb",
        "fem.materials.soil.preset": "medium_dense_sand",
        "fem.pushover.displacement": 0.04,
        "fem.pushover.increment": 0.002,
        "fem.pushover.unload_at": [0.02],
        "fit.width": 27.78,
    })
    fem = scene.resolved["fem"]
    assert fem["pushover"]["displacement"] == pytest.approx(0.04, rel=1e-12)
    assert fem["pushover"]["unload_at"] == pytest.approx([0.02], rel=1e-12)
    assert fem["pushover"]["increment"] == pytest.approx(0.002, rel=1e-12)
    result = kimp.study(scene, tmp_path / "out")
    element = result["yielding_wall"]["element"]
    # The element's resistance is its height's pushover, in SI with units per column.
    assert element["source"] == ["pushover"], element["source_reason"]
    assert element["bilinear_capacity"].units == "N/m"
    assert element["bilinear_stiffness"].units == "N/m/m"
    assert element["pushover_displacement"].units == "m"
    cap, k = float(element["bilinear_capacity"][0]), float(element["bilinear_stiffness"][0])
    alpha = float(element["bilinear_hardening_ratio"][0])
    w_d = float(element["pushover_displacement"][0])
    assert w_d == pytest.approx(0.04, rel=1e-9)
    assert cap + alpha * k * (w_d - cap / k) == pytest.approx(float(element["pushover_force"][0]),
                                                               rel=1e-9)
    # The element runs on the curve's concave hull, which ends at the largest force; the
    # bilinear above is the comparison.
    assert element["envelope"] == ["hull"]
    assert float(element["envelope_force"][0]) == pytest.approx(
        float(element["pushover_force"][0]), rel=1e-12)
    assert float(element["envelope_displacement"][0]) == pytest.approx(w_d, rel=1e-12)
    # The cyclic path was run: the curve's set at 20 mm is read.
    assert float(element["pushover_permanent_set"][0]) >= 0.0
    runs = result["yielding_wall"]["runs"]
    assert runs["residual_wall_displacement"].units == "m"
