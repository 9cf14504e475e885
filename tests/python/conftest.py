"""Fixtures of the Python API tests: the `kimp` executable of the same build, the source tree,
and small scenes (synthetic motion, so no records directory is needed)."""

import os
import shutil
import subprocess

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
