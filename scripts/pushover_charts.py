#!/usr/bin/python3
"""Chart of `kimp fem --pushover DIR`: band force against band displacement per wall height
(monotonic envelope, unloading and reloading branches). Reads DIR/pushover.h5; writes
DIR/charts/pushover.png and pushover.svg, each under a temporary name then renamed."""
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def save(fig, out_dir, name):
    for ext in ("png", "svg"):
        final = os.path.join(out_dir, f"{name}.{ext}")
        temporary = os.path.join(out_dir, f".{name}.tmp-{os.getpid()}.{ext}")
        fig.savefig(temporary, dpi=130, bbox_inches="tight")
        os.replace(temporary, final)
    plt.close(fig)


def main(directory):
    out_dir = os.path.join(directory, "charts")
    os.makedirs(out_dir, exist_ok=True)
    with h5py.File(os.path.join(directory, "pushover.h5"), "r") as h5:
        root = h5["pushover"]
        cases = sorted((c for c in root.keys() if c != "summary"),
                       key=lambda c: float(root[c].attrs["wall_height"]))
        fig, ax = plt.subplots(figsize=(6.0, 4.0), constrained_layout=True)
        for case in cases:
            curve = root[case]["curve"]
            u = curve["displacement"][()] * 1e3
            f = curve["force"][()] / 1e3
            ax.plot(u, f, "-", lw=1.4, label=f"H = {float(root[case].attrs['wall_height']):g} m")
        ax.set_xlabel("band displacement (mm)")
        ax.set_ylabel("band force (kN/m)")
        ax.set_title("Static pushover of wall and backfill")
        ax.grid(True, alpha=0.3)
        ax.legend()
        save(fig, out_dir, "pushover")


if __name__ == "__main__":
    main(sys.argv[1])
