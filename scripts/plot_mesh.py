#!/usr/bin/python3
"""PNG preview of a kimp scene mesh (ASCII MSH 4.1 as written by geometry/build_scene_mesh).

Draws the quads coloured by material (physical surface) and the tagged boundary lines coloured by
boundary id, once for the whole scene and once zoomed on the contact (wall face and slab front).
Usage: plot_mesh.py MESH.msh [-o PREVIEW.png] [--zoom HALF_WIDTH_M]
Needs only the Python standard library, numpy and matplotlib (Debian python3-matplotlib).
"""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402

MATERIAL_COLOURS = {1: "#9ecae1", 2: "#bdbdbd", 3: "#d8b365"}
BOUNDARY_COLOURS = {1: "#000000", 2: "#2ca25f", 3: "#e6550d", 4: "#756bb1"}


def read_msh41(path):
    """Nodes {tag: (x, y)}, quads [(material, [n1..n4])], lines [(boundary, [n1, n2])], names."""
    with open(path) as f:
        lines = [line.strip() for line in f]
    if not lines or lines[0] != "$MeshFormat" or not lines[1].startswith("4.1 0"):
        raise ValueError(f"{path}: not an ASCII MSH 4.1 file (header {lines[:2]})")

    def section(name):
        start = lines.index(f"${name}") + 1
        return lines[start:lines.index(f"$End{name}", start)]

    names = {}
    if "$PhysicalNames" in lines:
        for entry in section("PhysicalNames")[1:]:
            dim, tag, name = entry.split(maxsplit=2)
            names[(int(dim), int(tag))] = name.strip('"')

    # Physical tag of every entity (dim, tag); kimp writes exactly one per entity.
    physical = {}
    entities = section("Entities")
    counts = [int(v) for v in entities[0].split()]
    row = 1
    for dim, count in enumerate(counts):
        for _ in range(count):
            values = entities[row].split()
            row += 1
            tag = int(values[0])
            n_physical_at = 4 if dim == 0 else 7
            n_physical = int(values[n_physical_at])
            tags = [int(v) for v in values[n_physical_at + 1:n_physical_at + 1 + n_physical]]
            physical[(dim, tag)] = tags[0] if tags else 0

    nodes = {}
    block = section("Nodes")
    n_blocks = int(block[0].split()[0])
    row = 1
    for _ in range(n_blocks):
        _, _, parametric, n = (int(v) for v in block[row].split())
        if parametric:
            raise ValueError(f"{path}: parametric node coordinates are not supported")
        tags = [int(block[row + 1 + k]) for k in range(n)]
        for k, tag in enumerate(tags):
            x, y, _ = (float(v) for v in block[row + 1 + n + k].split())
            nodes[tag] = (x, y)
        row += 1 + 2 * n

    quads, segments = [], []
    block = section("Elements")
    n_blocks = int(block[0].split()[0])
    row = 1
    for _ in range(n_blocks):
        dim, entity, element_type, n = (int(v) for v in block[row].split())
        for k in range(n):
            connectivity = [int(v) for v in block[row + 1 + k].split()[1:]]
            group = physical.get((dim, entity), 0)
            if element_type == 3:
                quads.append((group, connectivity))
            elif element_type == 1:
                segments.append((group, connectivity))
            else:
                raise ValueError(f"{path}: element type {element_type} (expected 1 or 3)")
        row += 1 + n
    return nodes, quads, segments, names


def draw(ax, nodes, quads, segments, names, title):
    polygons = [[nodes[n] for n in q] for _, q in quads]
    colours = [MATERIAL_COLOURS.get(m, "#ffffff") for m, _ in quads]
    ax.add_collection(PolyCollection(polygons, facecolors=colours, edgecolors="#404040",
                                     linewidths=0.2))
    for boundary in sorted({b for b, _ in segments}):
        lines = [[nodes[n] for n in s] for b, s in segments if b == boundary]
        ax.add_collection(LineCollection(lines, colors=BOUNDARY_COLOURS.get(boundary, "red"),
                                         linewidths=2.0,
                                         label=f"{boundary}: {names.get((1, boundary), '')}"))
    for material in sorted({m for m, _ in quads}):
        ax.fill([], [], color=MATERIAL_COLOURS.get(material, "#ffffff"),
                label=f"{material}: {names.get((2, material), '')}")
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mesh", help="ASCII MSH 4.1 file")
    parser.add_argument("-o", "--output", help="PNG file (default: MESH with .png)")
    parser.add_argument("--zoom", type=float, default=0.4,
                        help="half width in m of the contact close-up around x = 0 (default 0.4)")
    args = parser.parse_args(argv)

    nodes, quads, segments, names = read_msh41(args.mesh)
    output = args.output or args.mesh.rsplit(".", 1)[0] + ".png"

    fig, (full, zoom) = plt.subplots(2, 1, figsize=(12, 9),
                                     gridspec_kw={"height_ratios": [1, 1.4]})
    n_cells = len(quads)
    draw(full, nodes, quads, segments, names, f"{args.mesh}: {len(nodes)} nodes, {n_cells} quads")
    draw(zoom, nodes, quads, segments, names, "contact close-up")
    contact = [nodes[n] for b, s in segments if b in (3, 4) for n in s]
    y_values = [y for _, y in contact] or [y for _, y in nodes.values()]
    zoom.set_xlim(-args.zoom, args.zoom)
    zoom.set_ylim(min(y_values) - 0.1 * args.zoom, max(y_values) + 0.1 * args.zoom)
    zoom.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=8)
    fig.tight_layout()
    fig.savefig(output, dpi=150)
    print(output)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
