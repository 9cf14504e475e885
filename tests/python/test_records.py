"""kimp.lumped and kimp.ground_motion on recorded motions, against `kimp lumped`: a case with its
own record (cases[i].record), a record that is not found (the CLI's message and did-you-mean),
a run over the step budget refused as the CLI refuses it, and the samples of AT2 and two-column
files as read from the text itself."""

import math

import numpy as np
import pytest

import kimp
from conftest import run_cli

G = 9.80665  # m/s² per g, the AT2 unit "G"


def pulse(n, dt, amplitude_g, period):
    """A decaying sine of `amplitude_g` (g) and `period` (s): n samples at dt."""
    t = np.arange(n) * dt
    return amplitude_g * np.sin(2 * math.pi * t / period) * np.exp(-t / 2.0)


def write_at2(path, acceleration_g, dt):
    """A PEER AT2 file: four header lines, then five values a line in g (%15.6E)."""
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", "kimp test record, synthetic",
             "ACCELERATION TIME HISTORY IN UNITS OF G", f"{len(acceleration_g)}    {dt:.4f}    NPTS, DT"]
    for i in range(0, len(acceleration_g), 5):
        lines.append("".join(f"{a:15.6E}" for a in acceleration_g[i:i + 5]))
    path.write_text("\n".join(lines) + "\n")


def at2_values(path):
    """The samples of an AT2 file parsed by Python from its text (g)."""
    lines = path.read_text().splitlines()
    return np.array([float(v) for line in lines[4:] for v in line.split()])


@pytest.fixture
def records(tmp_path):
    """A records directory with two AT2 records of different PGA (0.3 g and 0.5 g)."""
    directory = tmp_path / "records"
    directory.mkdir()
    write_at2(directory / "SITE_A.AT2", pulse(400, 0.01, 0.3, 0.8), 0.01)
    write_at2(directory / "SITE_B.AT2", pulse(500, 0.01, 0.5, 1.1), 0.01)
    return directory


CASE_RECORD_SCENE = """\
walls:
  left:
    gap: "3 cm"
  right:
    gap: "3 cm"
ground_motion:
  record: SITE_A
integration:
  output_interval: "0.01 s"
cases:
  - name: a
  - name: b
    record: SITE_B
"""


def test_a_case_s_own_record_equals_the_cli_bit_for_bit(tmp_path, records):
    path = tmp_path / "scene.yaml"
    path.write_text(CASE_RECORD_SCENE)
    run_cli("lumped", path, "-o", tmp_path / "out", "--records-dir", records)
    cli = kimp.read(tmp_path / "out" / "lumped.h5")["lumped"]
    results = kimp.lumped(path, records_dir=records)
    assert results.names == ["a", "b"]
    for r in results:
        group = cli[r.name]
        assert group.status == "ok" and r.ok
        assert r.pga == group["pga"]
        for key in ("displacement", "absolute_acceleration", "interstorey_drift"):
            np.testing.assert_array_equal(getattr(r.peaks, key), group["peaks"][key])
        np.testing.assert_array_equal(r.history.time, group["history"]["displacement"].time)
        np.testing.assert_array_equal(r.history.displacement,
                                      group["history"]["displacement"].value)
        np.testing.assert_array_equal(r.history.contact_force,
                                      group["history"]["contact_force"].value)
        assert r.n_steps == group["n_steps"][0]
    # Each case ran on its own record: the PGA of the file it names (0.3 g, 0.5 g to the
    # 7 digits of the AT2 text), so case b did not run on the scene's record.
    a, b = results["a"], results["b"]
    assert a.pga == pytest.approx(0.3 * G * np.max(np.abs(pulse(400, 0.01, 1, 0.8))), rel=1e-5)
    assert b.pga == pytest.approx(0.5 * G * np.max(np.abs(pulse(500, 0.01, 1, 1.1))), rel=1e-5)
    assert b.duration == pytest.approx(5.0) and a.duration == pytest.approx(4.0)
    # A single case of the scene runs on its own record too.
    alone = kimp.lumped(path, records_dir=records, case="b")
    np.testing.assert_array_equal(alone.peaks.displacement, b.peaks.displacement)


def test_a_missing_case_record_raises_the_cli_s_scene_error(tmp_path, records):
    path = tmp_path / "scene.yaml"
    path.write_text(CASE_RECORD_SCENE.replace("record: SITE_B", "record: SITE_BB"))
    cli = run_cli("lumped", path, "-o", tmp_path / "out", "--records-dir", records, check=False)
    assert cli.returncode == 1
    with pytest.raises(kimp.SceneError) as caught:
        kimp.lumped(path, records_dir=records)
    assert cli.stderr.strip() == f"error: {caught.value}"
    assert "did you mean 'SITE_B'?" in str(caught.value)
    assert caught.value.file == str(path)
    assert caught.value.line == 13
    assert caught.value.key == "cases[1].record"
    # As on the command line, nothing ran: the records are loaded before the first case.
    assert not (tmp_path / "out" / "lumped.h5").exists()


def test_a_run_over_the_step_budget_is_refused_like_the_cli(tmp_path, records):
    # 1e-6 s steps over the 4 s and 5 s records: 4e6 and 5e6 steps, above a budget of 1e6.
    budget = "integration:\n  max_steps: 1000000\n"
    path = tmp_path / "scene.yaml"
    path.write_text(CASE_RECORD_SCENE.replace("integration:\n", budget + '  dt: "1e-6 s"\n'))
    cli = run_cli("lumped", path, "-o", tmp_path / "out", "--records-dir", records, check=False)
    assert cli.returncode == 1
    with pytest.raises(RuntimeError) as caught:
        kimp.lumped(path, records_dir=records)
    assert cli.stderr.strip() == f"error: {caught.value}"
    assert str(caught.value).startswith("case a: 4e+06 steps of 1e-06 s")
    assert "exceeds the step budget integration.max_steps = 1e+06" in str(caught.value)
    assert not (tmp_path / "out" / "lumped.h5").exists()
    # Within the budget the same scene runs.
    path.write_text(CASE_RECORD_SCENE.replace("integration:\n", budget))
    assert all(r.ok for r in kimp.lumped(path, records_dir=records))


def test_at2_samples_are_the_file_s_values_in_si(tmp_path, records):
    motion = kimp.ground_motion(records / "SITE_B.AT2")
    g = at2_values(records / "SITE_B.AT2")
    np.testing.assert_array_equal(motion.acceleration, g * G)
    assert motion.dt == 0.01 and motion.name == "SITE_B"
    # scale multiplies, duration keeps the first samples (the reader's order: scale, trim).
    scaled = kimp.ground_motion(records / "SITE_B.AT2", scale=-1.5, duration="2 s")
    np.testing.assert_array_equal(scaled.acceleration, (g * G * -1.5)[:200])
    # The CLI's run of a scene on that record used the same motion: its PGA, bit for bit.
    path = tmp_path / "scene.yaml"
    path.write_text("ground_motion:\n  record: records/SITE_B.AT2\n  scale: -1.5\n"
                    "  duration: 2 s\n")
    run_cli("lumped", path, "-o", tmp_path / "out")
    assert kimp.read(tmp_path / "out" / "lumped.h5")["lumped/default/pga"] == scaled.pga
    assert scaled.pga == np.max(np.abs(scaled.acceleration))


def test_two_column_samples_are_the_file_s_values_in_si(tmp_path):
    t = np.arange(300) * 0.02
    a = 35.0 * np.sin(2 * math.pi * t / 0.9)  # cm/s²
    path = tmp_path / "motion.txt"
    path.write_text("".join(f"{ti!r} {ai!r}\n" for ti, ai in zip(t, a)))
    motion = kimp.ground_motion(path, record_unit="cm/s^2")
    text = np.loadtxt(path)
    np.testing.assert_array_equal(motion.acceleration, text[:, 1] * 0.01)
    assert motion.dt == pytest.approx(0.02, rel=1e-12)
    scene = tmp_path / "scene.yaml"
    scene.write_text("ground_motion:\n  record: motion.txt\n  record_unit: cm/s^2\n")
    run_cli("lumped", scene, "-o", tmp_path / "out")
    assert kimp.read(tmp_path / "out" / "lumped.h5")["lumped/default/pga"] == motion.pga
