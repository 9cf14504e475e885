"""kimp.lumped of a scene in plan against `kimp lumped` on the same scene: the same peaks (bit for
bit), histories per direction, rotation and corners consistent with the rigid slab, the energy
balance with friction work."""

import json

import numpy as np
import pytest

import kimp
from conftest import run_cli

# The default building on a 20 m square slab, mass 1 m off the centroid along x, in a moat at
# 4 cm with mu = 0.3, under 6 s of the synthetic motion at 30 degrees: corner impacts and torsion.
PLAN_SCENE = """\
ground_motion:
  duration: "6 s"
integration:
  dt: "2e-4 s"
  output_interval: "0.01 s"
plan:
  eccentricity_x: "1 m"
  angle: 30
  moat:
    gap: "4 cm"
    friction: 0.3
"""


def test_plan_run_equals_the_cli_and_keeps_the_slab_rigid(tmp_path):
    scene_file = tmp_path / "plan.yaml"
    scene_file.write_text(PLAN_SCENE)
    run_cli("lumped", scene_file, "-o", tmp_path / "out")
    cli = json.loads((tmp_path / "out" / "summary.json").read_text())["cases"][0]
    r = kimp.lumped(kimp.Scene.from_yaml(scene_file))
    assert isinstance(r, kimp.PlanResult) and r.ok
    assert r.n_levels == 5 and r.n_impacts == cli["n_impacts"] > 0
    for key in ("base_corner_displacement", "corner_impact_force", "friction_force",
                "top_acceleration", "isolator_force"):
        assert r.peaks[key] == cli["peaks"][key], key
    np.testing.assert_array_equal(r.peaks["displacement"].ravel(), cli["peaks"]["displacement"])
    np.testing.assert_array_equal(r.peaks["wall_force"], cli["peaks"]["wall_force"])
    assert r.energy["friction"] == cli["energy"]["friction"] > 0.0
    assert r.energy["max_relative_error"] < 1e-4

    # Per direction and rotation: (n, levels) histories whose peaks bound the samples.
    n = len(r.history["time"])
    assert r.x.shape == r.y.shape == r.rotation.shape == (n, 5)
    assert np.max(np.abs(r.rotation)) <= r.peaks["displacement"][:, 2].max()
    assert np.max(np.abs(r.rotation[:, 0])) > 1e-4, "the eccentric slab must turn"
    # The corners of level 0 move with the rigid slab: d = (u_x − θ·r_y, u_y + θ·r_x), r the
    # corner from the centre of mass (1 m off the centroid of the 20 m square).
    corners = np.array([[-10.0, -10.0], [10.0, -10.0], [10.0, 10.0], [-10.0, 10.0]]) - [1.0, 0.0]
    assert r.corners.shape == (n, 4, 2)
    u0, v0, t0 = r.x[:, 0], r.y[:, 0], r.rotation[:, 0]
    for k, (rx, ry) in enumerate(corners):
        np.testing.assert_allclose(r.corners[:, k, 0], u0 - t0 * ry, rtol=0, atol=1e-12)
        np.testing.assert_allclose(r.corners[:, k, 1], v0 + t0 * rx, rtol=0, atol=1e-12)
    assert r.history["contact_force"].shape == (n, len(r.contact_names))
    assert r.history["contact_force"].max() > 0.0


def test_planar_case_selection_is_refused_for_a_plan_scene():
    with pytest.raises(ValueError, match="no cases"):
        kimp.lumped(kimp.Scene(PLAN_SCENE), case="default")


def test_plan_yielding_faces_and_modal_damping_equal_the_cli(tmp_path):
    # Faces 1 and 3 (struck, at +x and -x) carry a weak wall-and-backfill part (5 kN/mm and
    # 20 kN per metre of the 20.08 m face, face 1 failing at 2 mm); modal damping.
    scene_text = PLAN_SCENE + (
        '    yielding:\n'
        '      - {face: 1, stiffness: "5 kN/mm/m", capacity: "20 kN/m", '
        'failure_displacement: "0.2 cm"}\n'
        '      - {face: 3, stiffness: "5 kN/mm/m", capacity: "20 kN/m"}\n'
        '  damping: modal\n')
    scene_file = tmp_path / "plan_yielding.yaml"
    scene_file.write_text(scene_text)
    run_cli("lumped", scene_file, "-o", tmp_path / "out")
    cli = json.loads((tmp_path / "out" / "summary.json").read_text())["cases"][0]
    r = kimp.lumped(kimp.Scene.from_yaml(scene_file))
    assert r.damping == cli["damping"]
    assert r.damping["model"] == "modal" and r.damping["damping_ratio"] == 0.02
    assert [w["face"] for w in r.yielding_walls] == [1, 3]
    assert r.yielding_walls == cli["yielding_walls"]
    assert r.yielding_walls[0]["failure_displacement"] == 0.002
    assert r.yielding_walls[1]["failure_displacement"] == pytest.approx(0.15)  # the default
    for w in r.yielding_walls:
        assert w["capacity"] == pytest.approx(20e3 * 20.08, rel=1e-12)
        assert w["peak_force"] == r.peaks["wall_force"][w["face"]]
        assert w["peak_resistance_ratio"] == w["peak_resistance"] / w["capacity"]
    assert all(w["peak_force"] > 0.0 and w["peak_resistance"] > 0.0 for w in r.yielding_walls)
    failed = [w for w in r.yielding_walls if w["failed"]]
    assert failed and all(w["failure_time"] > 0.0 and w["peak_displacement"] > 0.002
                          for w in failed)
    assert all(w["failure_time"] is None for w in r.yielding_walls if not w["failed"])
    # The walls' work in the balance: W_wall >= its plastic part, the balance closed.
    assert r.energy["wall_work"] >= r.energy["wall_plastic"] > 0.0
    assert r.energy["max_relative_error"] < 1e-3

    # The same scene with Rayleigh damping is a different run (the model reaches the engine).
    rayleigh = kimp.lumped(kimp.Scene(scene_text.replace("  damping: modal\n", "")))
    assert rayleigh.damping["model"] == "rayleigh"
    assert rayleigh.peaks["base_corner_displacement"] != r.peaks["base_corner_displacement"]
