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
