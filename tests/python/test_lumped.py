"""kimp.lumped against `kimp lumped` on the same scene: identical peaks and histories (bit for
bit), kimp.read of the CLI's lumped.h5, the GIL released during a run, memory flat over runs."""

import time

import numpy as np
import pytest

import kimp
from conftest import SHORT_SCENE, run_beside_a_python_thread, run_cli


def test_peaks_histories_and_impacts_equal_the_cli_bit_for_bit(tmp_path, pounding_scene_file):
    run_cli("lumped", pounding_scene_file, "-o", tmp_path / "out")
    cli = kimp.read(tmp_path / "out" / "lumped.h5")
    results = kimp.lumped(kimp.Scene.from_yaml(pounding_scene_file))
    assert results.names == ["kv", "hysteretic"]
    for r in results:
        group = cli["lumped"][r.name]
        assert group.status == "ok"
        assert r.n_impacts > 0, "the scene is meant to pound"
        for key in ("displacement", "absolute_acceleration", "interstorey_drift"):
            np.testing.assert_array_equal(getattr(r.peaks, key), group["peaks"][key])
            assert group["peaks"][key].units in ("m", "m/s^2")
        history = group["history"]
        np.testing.assert_array_equal(r.history.time, history["displacement"].time)
        np.testing.assert_array_equal(r.history.displacement, history["displacement"].value)
        np.testing.assert_array_equal(r.history.contact_force, history["contact_force"].value)
        np.testing.assert_array_equal(r.history.absolute_acceleration,
                                      history["absolute_acceleration"].value)
        assert history["contact_force"].units == "N"
        assert r.dt == group["dt"] and r.n_steps == group["n_steps"][0]
        assert r.pga == group["pga"]
        for contact in r.contacts:
            c = group["contacts"][contact.name]
            np.testing.assert_array_equal(contact.impact_time, c["impact_time"])
            assert contact.peak_force == c["peak_force"]
            assert contact.n_impacts == c.attrs["n_impacts"]
        assert r.energy.relative_error == group["energy"]["relative_error"]
        assert r.energy.input == group["energy"]["input"]
    # The results file carries the scene and the resolved parameters.
    assert cli.scene == pounding_scene_file.read_text()
    assert cli.resolved == kimp.Scene.from_yaml(pounding_scene_file).resolved


def test_single_case_and_case_selection(pounding_scene_file):
    one = kimp.lumped(pounding_scene_file, case="hysteretic")
    assert isinstance(one, kimp.Result) and one.name == "hysteretic"
    assert one.history.displacement.shape == (len(one.history.time), 5)
    assert one.history.interstorey_drift.shape[1] == 4
    assert "Result(name='hysteretic'" in repr(one) and "Peaks(" in repr(one.peaks)
    with pytest.raises(ValueError, match="no case 'nope'"):
        kimp.lumped(pounding_scene_file, case="nope")


def test_energy_balance_closes():
    r = kimp.lumped(kimp.Scene.from_dict(SHORT_SCENE))
    e = r.energy
    rhs = e.kinetic + e.strain + e.viscous + e.hysteretic + e.contact_work
    assert abs(e.initial + e.input - rhs) <= 1e-3 * (e.initial + abs(e.input))


def test_histories_are_numpy_views_of_the_engine_memory():
    r = kimp.lumped(kimp.Scene.from_dict(SHORT_SCENE))
    d = r.history.displacement
    # Owned by a capsule holding the engine's vector: not a numpy-allocated copy.
    assert not d.flags.owndata and d.base is not None
    assert d.flags.c_contiguous


def test_a_run_in_a_thread_does_not_block_other_python_threads():
    scene = kimp.Scene.from_dict({**SHORT_SCENE,
                                  "ground_motion": {"record": "synthetic", "duration": "20 s"},
                                  "integration": {"dt": "1e-6 s", "output_interval": "0.1 s"}})
    start = time.perf_counter()
    expected = kimp.lumped(scene)
    alone = time.perf_counter() - start
    assert alone > 0.1, "the run must be long enough to observe"
    result, longest_pause, ticks = run_beside_a_python_thread(lambda: kimp.lumped(scene))
    assert longest_pause < 0.5 * alone, (longest_pause, alone, ticks)
    assert ticks > 1000
    np.testing.assert_array_equal(result.peaks.displacement, expected.peaks.displacement)


def _rss_bytes():
    with open("/proc/self/statm") as f:
        import os
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_memory_stays_flat_over_1000_runs():
    scene = kimp.Scene.from_dict({**SHORT_SCENE,
                                  "ground_motion": {"record": "synthetic", "duration": "1 s"}})
    for _ in range(100):
        kimp.lumped(scene)
    before = _rss_bytes()
    for _ in range(1000):
        r = kimp.lumped(scene)
    growth = _rss_bytes() - before
    # One run's arrays are ~50 kB; a leak of one of them per run would add ~50 MB.
    assert growth < 8 * 2**20, f"RSS grew by {growth / 2**20:.1f} MiB over 1000 runs"
    assert r.peaks.displacement.shape == (5,)


def _cli_and_python(tmp_path, name, scene):
    """The scene (a dict) written as NAME.yaml and run by the CLI and by kimp.lumped: the CLI's
    case 'default' of lumped.h5 and the Python result."""
    scene_file = tmp_path / f"{name}.yaml"
    scene_file.write_text(kimp.Scene.from_dict(scene).to_yaml())
    run_cli("lumped", scene_file, "-o", tmp_path / "out")
    return kimp.read(tmp_path / "out" / "lumped.h5")["lumped"]["default"], kimp.lumped(scene_file)


def test_isolator_force_history_equals_the_cli_and_its_loop_dissipates(tmp_path):
    scene = dict(SHORT_SCENE, isolator={"kind": "bouc_wen", "K1": "200 MN/m", "K2": "25 MN/m",
                                        "Q_ratio": "10 %", "A": 1, "beta": 0.5, "gamma": 0.5,
                                        "n": 2},
                 integration={"output_interval": "1 ms"})
    group, r = _cli_and_python(tmp_path, "bouc_wen", scene)
    np.testing.assert_array_equal(r.history.isolator_force, group["history"]["isolator_force"].value)
    np.testing.assert_array_equal(r.history.hysteretic_energy,
                                  group["history"]["hysteretic_energy"].value)
    assert group["history"]["isolator_force"].units == "N"
    assert r.isolator.kind == "bouc_wen"
    assert r.isolator.peak_force == group["isolator"]["peak_force"]
    assert r.isolator.dissipated_energy == group["isolator"]["dissipated_energy"]
    # The sampled history holds the peak within the sampling, and the loop's area (the work of
    # the isolator force over the base displacement) is what the isolator dissipated plus what
    # it still stores elastically; its stored energy is at most F²/(2 K1).
    force = r.history.isolator_force
    assert np.max(np.abs(force)) <= r.isolator.peak_force * (1 + 1e-12)
    assert np.max(np.abs(force)) > 0.95 * r.isolator.peak_force
    u = r.history.displacement[:, 0]
    work = np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(u))
    stored_max = force[-1] ** 2 / (2 * 200e6)
    assert r.isolator.dissipated_energy > 0
    assert abs(work - r.isolator.dissipated_energy) <= stored_max + 0.02 * r.isolator.dissipated_energy


def test_no_isolator_gives_none_and_zero_force():
    r = kimp.lumped(kimp.Scene.from_dict({"building": {"kind": "fixed_base"},
                                          "walls": {"left": {"present": False},
                                                    "right": {"present": False}},
                                          "ground_motion": SHORT_SCENE["ground_motion"]}))
    assert r.isolator is None
    assert not np.any(r.history.isolator_force)


def test_read_paths_reach_the_datasets_of_a_time_series_and_miss_with_key_error(
        tmp_path, pounding_scene_file):
    run_cli("lumped", pounding_scene_file, "-o", tmp_path / "out")
    cli = kimp.read(tmp_path / "out" / "lumped.h5")
    series = cli["lumped/kv/history/displacement"]
    # The file's own paths: {step, time, value} of the time series group.
    np.testing.assert_array_equal(cli["lumped/kv/history/displacement/value"], series.value)
    np.testing.assert_array_equal(cli["/lumped/kv/history/displacement/time"], series.time)
    with pytest.raises(KeyError, match="no 'nope' in /lumped/kv/history/displacement"):
        cli["lumped/kv/history/displacement/nope"]
    with pytest.raises(KeyError, match="it is a dataset"):
        cli["lumped/kv/peaks/displacement/value"]
    with pytest.raises(KeyError, match="members: .*peaks"):
        cli["lumped/kv/nope"]


def test_yielding_walls_equal_the_cli(tmp_path):
    wall = {"gap": "4 cm", "sdof_mass": "50 t",
            "yielding": {"width": "20 m", "capacity": "50 kN/m", "stiffness": "10 kN/mm/m",
                         "failure_displacement": "1 cm"}}
    scene = dict(SHORT_SCENE, walls={"left": wall, "right": wall},
                 ground_motion={"record": "synthetic", "duration": "6 s"},
                 integration={"dt": "1e-4 s"})
    group, r = _cli_and_python(tmp_path, "yielding", scene)
    assert [w.name for w in r.walls] == ["left_wall", "right_wall"]
    assert any(w.peak_resistance_ratio >= 1.0 for w in r.walls), "the scene is meant to yield"
    for w in r.walls:
        g = group["walls"][w.name]
        assert w.peak_force == g["peak_force"] and w.capacity == g["capacity"] == 1e6
        assert w.peak_resistance == g["peak_resistance"] <= w.peak_force
        assert w.peak_displacement == g["peak_displacement"]
        assert w.residual_displacement == g["residual_displacement"]
        assert w.failed == bool(g.attrs["failed"])
        assert w.failed == (w.peak_displacement > 0.01)
    assert r.energy.wall_plastic > 0 and r.energy.wall_radiated > 0
    assert r.energy.relative_error < 1e-4


def test_yielding_walls_with_a_curve_envelope_equal_the_cli(tmp_path):
    # The curve envelope given as a list of {displacement, force} points; its capacity is the
    # last force (60 kN/m × 20 m), the run is the CLI's and closes its energy balance.
    curve = [{"displacement": "0 mm", "force": "0 kN/m"},
             {"displacement": "4 mm", "force": "40 kN/m"},
             {"displacement": "2 cm", "force": "60 kN/m"}]
    wall = {"gap": "4 cm", "sdof_mass": "50 t",
            "yielding": {"width": "20 m", "envelope": "curve", "curve": curve,
                         "unloading_stiffness": "5 kN/mm/m"}}
    scene = dict(SHORT_SCENE, walls={"left": wall, "right": wall},
                 ground_motion={"record": "synthetic", "duration": "6 s"},
                 integration={"dt": "1e-4 s"})
    group, r = _cli_and_python(tmp_path, "yielding_curve", scene)
    assert any(w.peak_resistance > 40e3 * 20 for w in r.walls), "the scene is meant to yield"
    for w in r.walls:
        g = group["walls"][w.name]
        assert w.capacity == g["capacity"] == pytest.approx(1.2e6, rel=1e-12)
        assert w.peak_force == g["peak_force"]
        assert w.residual_displacement == g["residual_displacement"]
    assert r.energy.wall_plastic > 0
    assert r.energy.relative_error < 1e-4
    # A convex point is refused with its key and index.
    bad = dict(wall, yielding=dict(wall["yielding"], curve=curve + [
        {"displacement": "3 cm", "force": "90 kN/m"}]))
    with pytest.raises(kimp.SceneError) as caught:
        kimp.Scene.from_dict(dict(scene, walls={"left": bad, "right": wall}))
    assert caught.value.key == "walls.left.yielding.curve[3]"
    assert "concave" in str(caught.value)
