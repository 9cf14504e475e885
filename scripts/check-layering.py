#!/usr/bin/env python3
"""Fails when a source file includes across a forbidden layer boundary (docs/architecture.md).

Every C++ file under a module directory may include headers of its own module and of the modules
listed for it below, and no third-party header of the families listed as foreign to it. Includes are
written from the repository root: a path with ".." (which could reach any layer) is refused, and so is
an included source file (*.cc): a command (cli/<name>_command.cc) is never included by another file.
Each module's CMakeLists.txt may link only the kimp targets of the modules it may include, so the
build graph says what the includes say.

Inside app/ and cli/ the rooms are checked too (APP_ROOMS). The lean executable links app/core
(the loose files of app/), app/laws (impact-law scenes, k sources, fits), app/lumped (lumped and
plan scenes and runs, collide), app/export (OpenSees) and app/sweep; the laws include no lumped
scene, the lumped runs no export; app/core, app/laws, app/lumped, app/export and app/sweep include
none of app/fem or app/study; app/sweep includes no study; server includes the lean rooms that
read and run scenes only; only the FEM part of cli/ (kimp-fem) includes app/fem and app/study. A header named *_internal.h is included only from its
own room. tests/ and bench/ may include any module, but no module includes tests/ or bench/.

    check-layering.py [ROOT]       check the tree at ROOT (default: the repository)
    check-layering.py --self-test  check that deliberate violations are caught
"""
import os
import re
import sys
import tempfile

# module -> kimp modules it may include (besides itself)
ALLOWED = {
    "base": set(),
    "lumped": set(),
    "geometry": set(),
    "fem": {"geometry"},
    "fit": {"lumped"},
    "io": {"base"},
    "report": {"base", "io"},
    "app": {"base", "io", "fit", "lumped", "geometry", "fem", "report"},
    "server": {"base", "io", "app", "report"},
    "cli": {"base", "io", "app", "report", "server"},
    "python": {"base", "io", "fit", "lumped", "app"},
}
MODULES = set(ALLOWED)

# room -> app rooms it may include. A file's room: its sub-directory of app/ (APP_SUBROOMS), or
# app/core (the loose files of app/); cli/fem for the commands of kimp-fem, cli/core for the rest.
LEAN = {"app/core", "app/laws", "app/lumped", "app/export", "app/sweep"}
APP_ROOMS = {
    "app/core": {"app/core"},
    "app/laws": {"app/core", "app/laws"},
    "app/lumped": {"app/core", "app/laws", "app/lumped"},
    "app/export": {"app/core", "app/laws", "app/lumped", "app/export"},
    "app/sweep": {"app/core", "app/laws", "app/lumped", "app/export", "app/sweep"},
    "app/fem": {"app/core", "app/laws", "app/fem"},
    "app/study": {"app/core", "app/laws", "app/lumped", "app/export", "app/fem", "app/study"},
    "server": {"app/core", "app/laws", "app/lumped"},
    "python": LEAN | {"app/fem", "app/study"},
    "cli/core": LEAN,
    "cli/fem": LEAN | {"app/fem", "app/study"},
}
APP_SUBROOMS = ("laws", "lumped", "export", "sweep", "fem", "study")
CLI_FEM = {"fem_command.cc", "mesh_command.cc", "study_command.cc", "fem_main.cc", "fem_commands.cc"}


def room_of(rel):
    """The room of a repository-relative path (see APP_ROOMS), or its top directory."""
    parts = rel.split("/")
    if parts[0] == "app":
        return "app/" + parts[1] if len(parts) > 2 and parts[1] in APP_SUBROOMS \
            else "app/core"
    if parts[0] == "cli":
        return "cli/fem" if parts[-1] in CLI_FEM else "cli/core"
    return parts[0]


def room_violation(rel, header):
    """Why `rel` may not include the kimp header `header` (None when it may)."""
    room, target = room_of(rel), room_of(header)
    if header.split("/")[0] in ("tests", "bench"):
        return f"{rel.split('/')[0]}/ includes nothing of {header.split('/')[0]}/"
    if os.path.basename(header).endswith("_internal.h") and room != target:
        return f"{header} is internal to {target}/"
    if target.startswith("app/") and room in APP_ROOMS and target not in APP_ROOMS[room]:
        allowed = ", ".join(sorted(APP_ROOMS[room]))
        return f"{room} may include {allowed} of app/, not {target}"
    return None

# module -> third-party header prefixes it must not include
FOREIGN = {
    "base": ["deal.II/", "gmsh", "hdf5", "H5", "yaml-cpp/", "CLI/", "Eigen/", "mpi.h"],
    "lumped": ["deal.II/", "gmsh", "hdf5", "H5", "yaml-cpp/", "nlohmann/", "CLI/", "spdlog/", "mpi.h"],
    "geometry": ["deal.II/", "hdf5", "H5", "yaml-cpp/", "nlohmann/", "CLI/", "spdlog/"],
    "fem": ["hdf5", "H5", "yaml-cpp/", "nlohmann/", "CLI/", "spdlog/"],
    "fit": ["deal.II/", "gmsh", "hdf5", "H5", "yaml-cpp/", "nlohmann/", "CLI/", "mpi.h"],
    "io": ["deal.II/", "gmsh", "Eigen/", "CLI/", "httplib"],
    "app": ["CLI/", "hdf5", "H5", "httplib"],
    "report": ["deal.II/", "gmsh", "hdf5", "H5", "yaml-cpp/", "Eigen/", "CLI/", "httplib", "mpi.h"],
    "server": ["deal.II/", "gmsh", "hdf5", "H5", "Eigen/", "CLI/"],
    "cli": ["deal.II/", "gmsh", "hdf5", "H5", "yaml-cpp/", "httplib"],
    "python": ["deal.II/", "gmsh", "hdf5", "H5", "yaml-cpp/", "CLI/"],
}

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)
COMMAND = re.compile(r"^cli/(\w+)_command\.(cc|h)$")
# kimp::<target> -> the module it belongs to (a module may build several targets)
TARGET_MODULE = {"app_core": "app", "app_mpi_ranks": "app", "app_single_rank": "app",
                 "cli_core": "cli", "test_support": "tests"}
KIMP_TARGET = re.compile(r"\bkimp::(\w+)")


def violations(root):
    found = []
    for module in sorted(MODULES):
        top = os.path.join(root, module)
        for directory, _, files in os.walk(top):
            for name in sorted(files):
                if not name.endswith((".h", ".cc", ".h.in")):
                    continue
                path = os.path.join(directory, name)
                rel = os.path.relpath(path, root).replace(os.sep, "/")
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                for match in INCLUDE.finditer(text):
                    kind, header = match.groups()
                    line = text.count("\n", 0, match.start()) + 1
                    first = header.split("/")[0]
                    where = f"{rel}:{line}: #include {kind}{header}{'>' if kind == '<' else kind}"
                    if kind == '"' and ".." in header.split("/"):
                        found.append(f"{where}: write includes from the repository root, without '..'")
                        continue
                    if kind == '"' and header.endswith(".cc"):
                        found.append(f"{where}: a source file is compiled, never included")
                        continue
                    if kind == '"' and first in MODULES | {"tests", "bench"} and "/" in header:
                        why = room_violation(rel, header)
                        if why:
                            found.append(f"{where}: {why}")
                    if first in MODULES and "/" in header:
                        if first != module and first not in ALLOWED[module]:
                            allowed = ", ".join(sorted(ALLOWED[module])) or "nothing else of kimp"
                            found.append(f"{where}: {module}/ may include {allowed}, not {first}/")
                        command = COMMAND.match(rel)
                        other = COMMAND.match(header)
                        if command and other and other.group(1) != command.group(1):
                            found.append(f"{where}: a command includes no other command")
                    elif kind == "<" or first not in MODULES:
                        for prefix in FOREIGN[module]:
                            if header.startswith(prefix):
                                found.append(f"{where}: {module}/ must not depend on <{prefix}...>")
    return found + link_violations(root)


def link_violations(root):
    """kimp targets linked by a module's CMakeLists.txt that the module may not include."""
    found = []
    for module in sorted(MODULES):
        path = os.path.join(root, module, "CMakeLists.txt")
        if not os.path.isfile(path):
            continue
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for match in KIMP_TARGET.finditer(text):
            target = match.group(1)
            line_start = text.rfind("\n", 0, match.start()) + 1
            if text[line_start:match.start()].lstrip().startswith("#"):
                continue
            other = TARGET_MODULE.get(target, target)
            if other != module and other not in ALLOWED[module]:
                line = text.count("\n", 0, match.start()) + 1
                allowed = ", ".join(sorted(ALLOWED[module])) or "nothing else of kimp"
                found.append(f"{module}/CMakeLists.txt:{line}: links kimp::{target}: "
                             f"{module}/ may use {allowed}, not {other}/")
    return found


def self_test():
    cases = {
        "lumped/laws/x.h": '#include "io/units.h"\n',
        "io/x.cc": '#include "lumped/laws/force_law.h"\n',
        "fit/x.cc": '#include "fem/impact.h"\n',
        "cli/lumped_command.cc": '#include "cli/fit_command.cc"\n',
        "fem/x.cc": '#include "app/lumped/lumped_run.h"\n',
        "lumped/y.cc": "#include <hdf5.h>\n",
        "report/x.cc": '#include "app/lumped/lumped_run.h"\n',
        "lumped/z.cc": '#include "server/server.h"\n',
        "app/x.cc": "#include <httplib.h>\n",
        "app/y.cc": '#include "python/bindings.h"\n',
        "python/x.cc": "#include <CLI/CLI.hpp>\n",
        "lumped/w.cc": '#include "../io/units.h"\n',
        "lumped/v.cc": '#include "lumped/../io/units.h"\n',
        "cli/commands.cc": '#include "cli/study_command.cc"\n',
        "fit/CMakeLists.txt": "target_link_libraries(kimp_fit PUBLIC kimp::lumped kimp::io)\n",
        "io/CMakeLists.txt": "target_link_libraries(kimp_io PRIVATE kimp::app_core)\n",
        "server/y.cc": '#include "app/study/study_run.h"\n',
        "app/y2.cc": '#include "app/fem/fem_run.h"\n',
        "app/sweep/x.cc": '#include "app/study/study_internal.h"\n',
        "io/y.cc": '#include "tests/support/kimp_run.h"\n',
        "app/fem/x.cc": '#include "app/lumped/lumped_run_internal.h"\n',
        "cli/sweep_command.cc": '#include "app/study/study_run.h"\n',
        "app/laws/x.cc": '#include "app/lumped/lumped_scene.h"\n',
        "app/lumped/x.cc": '#include "app/export/opensees_export.h"\n',
        "app/lumped/y.cc": '#include "app/fem/fem_scene.h"\n',
    }
    with tempfile.TemporaryDirectory() as root:
        for rel, text in cases.items():
            path = os.path.join(root, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        found = violations(root)
    missed = [rel for rel in cases if not any(v.startswith(rel + ":") for v in found)]
    if missed:
        print("check-layering self-test: violations not detected in " + ", ".join(missed))
        return 1
    print(f"check-layering self-test: all {len(cases)} deliberate violations detected")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    root = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    found = violations(root)
    for v in found:
        print(v)
    if found:
        print(f"check-layering: {len(found)} include(s) cross a forbidden layer boundary "
              "(see docs/architecture.md)")
        return 1
    print("check-layering: every include respects the layers")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
