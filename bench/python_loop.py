#!/usr/bin/env python3
"""A loop of short lumped runs from Python: kimp.lumped in memory against `kimp lumped` in a
subprocess per run (scene file written, results read back from peaks.csv), same scenes; both loops' peaks are compared bit for bit.

    PYTHONPATH=build/python python3 bench/python_loop.py [--kimp build/kimp] [--runs 1000]
                                                          [--subprocess-runs 50]

Each run is the thesis building (docs/physics.md §2) on moat walls under 3 s of the synthetic
near-fault motion, the wall gap varied from run to run. The subprocess loop is timed over
--subprocess-runs runs and scaled to --runs (its cost per run is constant); the first runs of
each loop also check that both give the same peak isolation displacement.
"""

import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time

import kimp

SCENE = {
    "walls": {"left": {"gap": "6 cm"}, "right": {"gap": "6 cm"}},
    "ground_motion": {"record": "synthetic", "duration": "3 s"},
    "integration": {"output_interval": "0.01 s"},
}


def gap(i):
    """Wall gap of run i, m: 4-10 cm."""
    return 0.04 + 0.06 * (i % 100) / 100


def api_loop(runs):
    base = kimp.Scene.from_dict(SCENE)
    peaks = []
    start = time.perf_counter()
    for i in range(runs):
        scene = base.with_(walls={"left": {"gap": gap(i)}, "right": {"gap": gap(i)}})
        peaks.append(kimp.lumped(scene).peaks.displacement[0])
    return time.perf_counter() - start, peaks


def subprocess_loop(runs, executable):
    """Seconds of the loop, and the exact peaks (from lumped.h5, read after the timing)."""
    base = kimp.Scene.from_dict(SCENE)
    with tempfile.TemporaryDirectory(prefix="kimp-bench-") as work:
        start = time.perf_counter()
        for i in range(runs):
            path = os.path.join(work, f"scene{i}.yaml")
            base.with_(walls={"left": {"gap": gap(i)}, "right": {"gap": gap(i)}}).write(path)
            out = os.path.join(work, f"out{i}")
            subprocess.run([executable, "-q", "lumped", path, "-o", out], check=True)
            with open(os.path.join(out, "peaks.csv"), newline="") as f:
                float(next(csv.DictReader(f))["peak_displacement_m"])
        seconds = time.perf_counter() - start
        peaks = [kimp.read(os.path.join(work, f"out{i}", "lumped.h5"))
                 ["lumped/default/peaks/displacement"][0] for i in range(runs)]
        return seconds, peaks


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kimp", default=os.environ.get("KIMP_EXECUTABLE", "build/kimp"))
    parser.add_argument("--runs", type=int, default=1000)
    parser.add_argument("--subprocess-runs", type=int, default=50)
    args = parser.parse_args()

    api_seconds, api_peaks = api_loop(args.runs)
    n_sub = min(args.subprocess_runs, args.runs)
    sub_seconds, sub_peaks = subprocess_loop(n_sub, args.kimp)
    mismatch = [i for i in range(n_sub) if api_peaks[i] != sub_peaks[i]]
    per_api = api_seconds / args.runs
    per_sub = sub_seconds / n_sub
    print(f"kimp.lumped in Python : {args.runs} runs in {api_seconds:.3f} s "
          f"({per_api * 1e3:.2f} ms per run)")
    print(f"kimp lumped subprocess: {n_sub} runs in {sub_seconds:.3f} s "
          f"({per_sub * 1e3:.1f} ms per run; {per_sub * args.runs:.1f} s for {args.runs})")
    print(f"speed-up: {per_sub / per_api:.0f}x (target >= 50x); identical peaks: "
          f"{n_sub - len(mismatch)}/{n_sub}")
    return 1 if mismatch else 0


if __name__ == "__main__":
    sys.exit(main())
