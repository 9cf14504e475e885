#!/usr/bin/env python3
"""A loop of short lumped runs from Python: kimp.lumped in memory against `kimp lumped` in a
subprocess per run (scene file written, results read back from peaks.csv), same scenes; both
loops' peaks are compared bit for bit.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_loop.py [--kimp build/kimp]
        [--runs 1000] [--subprocess-runs 1000]

Each run is the thesis building (docs/physics.md §2) on moat walls under 3 s of the synthetic
near-fault motion, the wall gap varied from run to run (4-10 cm), histories recorded every
0.01 s in both loops (the API returns them as arrays, the CLI writes them to lumped.h5). Both
loops run --runs times by default (1,000: about 35 s of subprocesses); a smaller
--subprocess-runs times that loop over fewer runs and scales it. Wall time and CPU time (this
process plus its children) are reported for both: on a shared machine the CPU time is the
steadier measure. The peak isolation displacements of every subprocess run are compared with
the API's.
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


def cpu_seconds():
    """CPU time (user + system) of this process and its finished children, s."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def api_loop(runs):
    """(wall s, CPU s, peaks) of `runs` runs: a new scene (with_) and kimp.lumped each."""
    base = kimp.Scene.from_dict(SCENE)
    peaks = []
    start, cpu = time.perf_counter(), cpu_seconds()
    for i in range(runs):
        scene = base.with_(walls={"left": {"gap": gap(i)}, "right": {"gap": gap(i)}})
        peaks.append(kimp.lumped(scene).peaks.displacement[0])
    return time.perf_counter() - start, cpu_seconds() - cpu, peaks


def subprocess_loop(runs, executable):
    """(wall s, CPU s, exact peaks from lumped.h5, read after the timing) of `runs` runs."""
    base = kimp.Scene.from_dict(SCENE)
    with tempfile.TemporaryDirectory(prefix="kimp-bench-") as work:
        start, cpu = time.perf_counter(), cpu_seconds()
        for i in range(runs):
            path = os.path.join(work, f"scene{i}.yaml")
            base.with_(walls={"left": {"gap": gap(i)}, "right": {"gap": gap(i)}}).write(path)
            out = os.path.join(work, f"out{i}")
            subprocess.run([executable, "-q", "lumped", path, "-o", out], check=True)
            with open(os.path.join(out, "peaks.csv"), newline="") as f:
                float(next(csv.DictReader(f))["peak_displacement_m"])
        seconds, cpu = time.perf_counter() - start, cpu_seconds() - cpu
        peaks = [kimp.read(os.path.join(work, f"out{i}", "lumped.h5"))
                 ["lumped/default/peaks/displacement"][0] for i in range(runs)]
        return seconds, cpu, peaks


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kimp", default=os.environ.get("KIMP_EXECUTABLE", "build/kimp"))
    parser.add_argument("--runs", type=int, default=1000)
    parser.add_argument("--subprocess-runs", type=int, default=None,
                        help="subprocess runs (default: --runs; fewer are scaled to --runs)")
    args = parser.parse_args()

    api_loop(min(args.runs, 20))  # module, synthetic motion and allocator warm, as in a session
    api_wall, api_cpu, api_peaks = api_loop(args.runs)
    n_sub = min(args.subprocess_runs or args.runs, args.runs)
    sub_wall, sub_cpu, sub_peaks = subprocess_loop(n_sub, args.kimp)
    mismatch = [i for i in range(n_sub) if api_peaks[i] != sub_peaks[i]]
    load = os.getloadavg()[0]
    scaled = "" if n_sub == args.runs else f" (scaled from {n_sub})"
    print(f"machine: {os.cpu_count()} CPUs, load average {load:.1f}")
    print(f"kimp.lumped in Python : {args.runs} runs in {api_wall:.3f} s wall, {api_cpu:.3f} s CPU "
          f"({api_wall / args.runs * 1e3:.3f} ms wall, {api_cpu / args.runs * 1e3:.3f} ms CPU "
          f"per run)")
    print(f"kimp lumped subprocess: {n_sub} runs in {sub_wall:.2f} s wall, {sub_cpu:.2f} s CPU "
          f"({sub_wall / n_sub * 1e3:.2f} ms wall, {sub_cpu / n_sub * 1e3:.2f} ms CPU per run)"
          f"{scaled}")
    print(f"speed-up: {sub_wall / n_sub / (api_wall / args.runs):.0f}x wall, "
          f"{sub_cpu / n_sub / (api_cpu / args.runs):.0f}x CPU (target >= 50x); identical "
          f"peaks: {n_sub - len(mismatch)}/{n_sub}")
    return 1 if mismatch else 0


if __name__ == "__main__":
    sys.exit(main())
