"""Fixtures of the Python API tests: the `kimp` executable of the same build, the source tree,
and small scenes (synthetic motion, so no records directory is needed)."""

import os
import shutil
import subprocess
import threading
import time

import pytest

SOURCE_DIR = os.environ.get("KIMP_SOURCE_DIR",
                            os.path.dirname(os.path.dirname(os.path.dirname(__file__))))


def kimp_executable():
    path = os.environ.get("KIMP_EXECUTABLE") or shutil.which("kimp")
    if not path or not os.path.exists(path):
        pytest.skip("the kimp executable is not known (set KIMP_EXECUTABLE)")
    return path


def run_cli(*args, check=True):
    """Run `kimp ARGS...`; returns the CompletedProcess (stdout and stderr as text)."""
    process = subprocess.run([kimp_executable(), "-q", *map(str, args)], capture_output=True,
                             text=True, cwd=SOURCE_DIR)
    if check and process.returncode != 0:
        raise AssertionError(f"kimp {' '.join(map(str, args))} failed:\n{process.stderr}")
    return process


# A 4-storey isolated building (thesis Table 4.2) on moat walls under 6 s of the synthetic
# near-fault motion: a few impacts on both walls, in about 20 ms.
POUNDING_SCENE = """\
building:
  n_storeys: 4
walls:
  left:
    gap: "8 cm"
  right:
    gap: "8 cm"
impact:
  law: modified_kelvin_voigt
  k: "2500 kN/mm"
ground_motion:
  record: synthetic
  duration: "6 s"
integration:
  output_interval: "0.01 s"
cases:
  - name: kv
  - name: hysteretic
    law: hysteretic
    k: "750 kN/mm^1.5"
"""

SHORT_SCENE = {
    "walls": {"left": {"gap": 0.06}, "right": {"gap": 0.06}},
    "ground_motion": {"record": "synthetic", "duration": "3 s"},
}


@pytest.fixture
def pounding_scene_file(tmp_path):
    path = tmp_path / "pounding.yaml"
    path.write_text(POUNDING_SCENE)
    return path


def run_beside_a_python_thread(run):
    """Run `run()` in a thread while this thread counts loop turns; returns (its result, the
    longest pause of this thread's loop, s, and the turns). With the GIL held for the whole run
    this thread would stop for the run's duration; with it released it only yields at Python's
    switch interval (5 ms)."""
    results = []
    worker = threading.Thread(target=lambda: results.append(run()))
    ticks, longest_pause = 0, 0.0
    last = time.perf_counter()
    worker.start()
    while worker.is_alive():
        now = time.perf_counter()
        longest_pause = max(longest_pause, now - last)
        last = now
        ticks += 1
    worker.join()
    assert results, "the run raised in its thread"
    return results[0], longest_pause, ticks


# A site study like the notebook's, at a fixed fidelity for speed: one wall height, an elastic
# slab, the study's mesh on a 5 cm contact mesh, the reference velocity only, rigid walls, the
# synthetic record, no charts or extra studies: seconds.
QUICK_STUDY = """\
fem:
  wall_heights: ["1.25 m"]
  mesh:
    h_contact: "5 cm"
  slab:
    velocity: "1.0 m/s"
  dynamics:
    end_time: "40 ms"
    output_interval: "0.02 ms"
  fidelity: fixed
  velocities: []
walls:
  flexible: false
records:
  - record: synthetic
peer_records: false
charts: false
stability_map: false
accuracy_study: false
"""
