#!/usr/bin/env python3
"""The docs are run: every command, option and repository file that README.md and docs/guide/
name must exist, and the README's example commands must run.

Usage: check_docs.py REPO_ROOT BUILD_DIR

Checks, each reported as `FILE:LINE: ...`:
- every `kimp <command>` in inline code or a code block is a command of `kimp --help`;
- every `--option` written in the same span after `kimp <command>` is in `kimp <command> --help`;
- every repository path written in backticks or as a link (data/, docs/, scripts/, examples/,
  bench/, tests/, gui/, python/) exists (a path with a wildcard or a placeholder in capitals is
  a pattern, not a file, and is skipped);
- every relative Markdown link resolves to a file;
- every line of the README's ```sh blocks that starts with ./build/kimp runs and exits 0 (outputs
  redirected into a temporary directory).
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile

ROOT, BUILD = (os.path.abspath(p) for p in sys.argv[1:3])
KIMP = os.path.join(BUILD, "kimp")
REPO_DIRS = ("data/", "docs/", "scripts/", "examples/", "bench/", "tests/", "gui/", "python/")
errors = []


def doc_files():
    yield os.path.join(ROOT, "README.md")
    guide = os.path.join(ROOT, "docs", "guide")
    for name in sorted(os.listdir(guide)):
        if name.endswith(".md"):
            yield os.path.join(guide, name)


def run(args, **kw):
    return subprocess.run(args, capture_output=True, text=True, timeout=120, **kw)


def commands():
    out = run([KIMP, "--help"]).stdout
    section = out.split("SUBCOMMANDS:", 1)[-1]
    return {m.group(1) for m in re.finditer(r"^\s{2}(\S+)", section, re.M)}


_help_cache = {}


def options_of(command):
    if command not in _help_cache:
        _help_cache[command] = run([KIMP, command, "--help"]).stdout
    return _help_cache[command]


def spans(text):
    """(line number, code text) of every inline code span and every code-block line."""
    in_block = False
    for number, line in enumerate(text.split("\n"), 1):
        if line.lstrip().startswith("```"):
            in_block = not in_block
            continue
        if in_block:
            if re.match(r"\s*(\$ )?(\./build/|build/)?(kimp |mpirun )", line):
                yield number, line
        else:
            for m in re.finditer(r"`([^`]+)`", line):
                if re.match(r"(\./build/|build/)?(kimp |mpirun )", m.group(1)):
                    yield number, m.group(1)


def check_commands(path, text, known):
    rel = os.path.relpath(path, ROOT)
    for number, code in spans(text):
        for m in re.finditer(r"(?:^|[\s/(])kimp\s+([a-z][a-z-]*)((?:[^|;&`]*)?)", code):
            command, rest = m.group(1), m.group(2)
            if command not in known:
                errors.append(f"{rel}:{number}: `kimp {command}` is not a kimp command")
                continue
            help_text = options_of(command)
            for option in re.findall(r"(?<![\w-])(--[a-z][a-z0-9-]*)", rest):
                if not re.search(r"(?<![\w-])" + re.escape(option) + r"(?![\w-])", help_text):
                    errors.append(f"{rel}:{number}: `kimp {command}` has no option {option}")


def check_paths(path, text):
    rel = os.path.relpath(path, ROOT)
    base = os.path.dirname(path)
    for number, line in enumerate(text.split("\n"), 1):
        for m in re.finditer(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", line):
            target = m.group(1)
            if re.match(r"[a-z]+:", target):
                continue
            if not os.path.exists(os.path.join(base, target)):
                errors.append(f"{rel}:{number}: link target {target} does not exist")
        for m in re.finditer(r"`([^`\s]+)`", line):
            candidate = m.group(1).rstrip(".,:;")
            if not candidate.startswith(REPO_DIRS):
                continue
            if re.search(r"[*<>{}]|[A-Z]{2,}|\.\.\.", candidate.split("/", 1)[1]):
                continue
            if not os.path.exists(os.path.join(ROOT, candidate)):
                errors.append(f"{rel}:{number}: `{candidate}` does not exist in the repository")


def run_readme_examples(text):
    in_sh = False
    with tempfile.TemporaryDirectory() as out:
        for number, line in enumerate(text.split("\n"), 1):
            if line.startswith("```"):
                in_sh = line.strip() == "```sh"
                continue
            if not in_sh or not line.startswith("./build/kimp "):
                continue
            args = shlex.split(line)
            command = args[1]
            if command in ("study", "fem", "mesh", "sweep", "gui", "export-opensees"):
                continue  # minutes of FEM, or a server: their options are checked above
            args[0] = KIMP
            # Outputs (and the report's input) go to the temporary directory.
            args = [os.path.join(out, a) if a.startswith("out/") else a for a in args]
            result = run(args, cwd=ROOT)
            if result.returncode != 0:
                errors.append(f"README.md:{number}: `{line}` exited {result.returncode}: "
                              f"{result.stderr.strip()[:300]}")


def main():
    known = commands()
    if not {"lumped", "study", "fit"} <= known:
        print(f"check_docs: cannot read the commands of {KIMP} --help", file=sys.stderr)
        return 1
    for path in doc_files():
        text = open(path, encoding="utf-8").read()
        check_commands(path, text, known)
        check_paths(path, text)
    run_readme_examples(open(os.path.join(ROOT, "README.md"), encoding="utf-8").read())
    readme_lines = open(os.path.join(ROOT, "README.md"), encoding="utf-8").read().count("\n")
    if readme_lines > 150:
        errors.append(f"README.md: {readme_lines} lines; the front page keeps to 150")
    for e in errors:
        print("error: " + e, file=sys.stderr)
    print(f"check_docs: {len(list(doc_files()))} pages, {len(errors)} errors")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
