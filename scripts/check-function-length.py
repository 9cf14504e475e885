#!/usr/bin/env python3
"""Lists the functions of kimp's sources longer than a limit that carry no note saying why.

Usage: check-function-length.py REPO_ROOT [--limit N] [--list N] [--baseline FILE]
       check-function-length.py --self-test

A function longer than --limit lines (default 120, signature to closing brace) must be split into
named steps, or say in the comment block right above its definition why it is one algorithm:
a line containing "Long by design:" followed by the reason. Exit status 1 lists the offenders as
FILE:LINE: name: N lines. `--list N` prints every function over N lines (with or without note),
longest first, and exits 0: the inventory for a refactoring.

`--baseline FILE` names functions still waiting for their split (one `path: name` per line, `#`
comments): they are reported but do not fail the check, so that no new long function can enter
while the old ones are worked off. A baseline entry that is no longer over the limit (split, or
given its note) fails the check until it is removed from the file: the list only shrinks.

The parser is a brace matcher over the source with comments, strings and preprocessor lines
blanked out, so it needs no compiler: a `{` opens a function when the text before it (since the
last `;`, `{` or `}`) ends in a parameter list, possibly followed by qualifiers, and it is not
inside another function. Lambdas and local classes count towards their enclosing function.
"""
import os
import re
import sys

MODULES = ("base", "lumped", "geometry", "fem", "fit", "io", "report", "app", "server", "cli",
           "python")
NOTE = "Long by design:"
CONTROL = {"if", "for", "while", "switch", "catch", "do", "else", "try", "return", "sizeof",
           "decltype", "alignas", "static_assert", "__attribute__"}
QUALIFIER_TAIL = re.compile(
    r"\)\s*((const|noexcept(\s*\([^()]*\))?|override|final|mutable|&&|&|->\s*[\w:<>,\s*&]+"
    r"|try)\s*)*$")


def blank(text):
    """Comments, string and character literals and preprocessor lines replaced by spaces
    (newlines kept, so that offsets keep their line numbers)."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#":
            j = i
            while j < n and text[j] != "\n":
                if text[j] == "\\" and j + 1 < n and text[j + 1] == "\n":
                    j += 2
                    out.append(" \n")
                    continue
                out.append(" ")
                j += 1
            i = j
            continue
        if c == "\n":
            at_line_start = True
            out.append(c)
            i += 1
            continue
        if not c.isspace():
            at_line_start = False
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
            continue
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
            continue
        m = re.match(r'R"([^(\s]*)\(', text[i:i + 20])
        if m:
            end = text.find(")" + m.group(1) + '"', i)
            end = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
            continue
        if c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + re.sub(r"[^\n]", " ", text[i + 1:j]) + c)
            i = j + 1
            continue
        out.append(c)
        i += 1
    return "".join(out)


def functions(text):
    """(name, first line, last line) of every outermost function definition."""
    code = blank(text)
    line_of = [0] * (len(code) + 1)
    line = 1
    for k, ch in enumerate(code):
        line_of[k] = line
        if ch == "\n":
            line += 1
    stack = []  # one entry per open brace: True if it opened a function (or is inside one)
    head_start = 0
    result = []
    for k, ch in enumerate(code):
        if ch in ";":
            if not any(stack):
                head_start = k + 1
        elif ch == "{":
            inside = any(stack)
            head = code[head_start:k]
            opens = False
            if not inside:
                flat = " ".join(head.split())
                m = re.search(r"([~\w:<>]+(?:operator\s*[^\s(]+)?)\s*\(", flat)
                first_word = flat.split(" ", 1)[0] if flat else ""
                if (m and QUALIFIER_TAIL.search(flat) and first_word not in CONTROL
                        and not re.match(r"(namespace|class|struct|enum|union)\b", flat)
                        and "=" not in flat.split("(", 1)[0]):
                    name = m.group(1)
                    if name.split("::")[-1] not in CONTROL:
                        opens = True
                        start = head_start + len(head) - len(head.lstrip())
                        stack.append(("fn", name, line_of[start]))
                        continue
            stack.append(inside)
            if not inside:
                head_start = k + 1
        elif ch == "}":
            if not stack:
                continue
            top = stack.pop()
            if isinstance(top, tuple):
                result.append((top[1], top[2], line_of[k]))
            if not any(stack):
                head_start = k + 1
    return result


def has_note(lines, first_line):
    """A comment block right above the definition (or its template line) with the note."""
    i = first_line - 2
    while i >= 0 and (lines[i].strip().startswith(("//", "*", "/*", "template")) or
                      lines[i].strip().endswith("*/")):
        if NOTE in lines[i]:
            return True
        i -= 1
    return False


def scan(root):
    for module in MODULES:
        for directory, _, names in os.walk(os.path.join(root, module)):
            for name in sorted(names):
                if name.endswith((".cc", ".h")):
                    path = os.path.join(directory, name)
                    text = open(path, encoding="utf-8", errors="replace").read()
                    lines = text.split("\n")
                    for fn, first, last in functions(text):
                        yield os.path.relpath(path, root), fn, first, last - first + 1, \
                            has_note(lines, first)


def self_test():
    sample = "\n".join([
        "namespace a {",
        "  int short_one(int x) { return x; }",
        "  // Long by design: one Newton loop.",
        "  void noted() {",
        *["    x();"] * 130,
        "  }",
        "  void too_long(const std::string &s) const",
        "  {",
        '    auto f = [&](int i) { if (i) { return "}"; } return "{"; };',
        *["    y(); // }"] * 130,
        "  }",
        "  struct S { void m() { } };",
        "}",
    ])
    found = {name: (first, last - first + 1) for name, first, last in functions(sample)}
    lines = sample.split("\n")
    expected = {"short_one": (2, 1), "noted": (4, 132), "too_long": (136, 134), "m": (270, 1)}
    ok = found == expected and has_note(lines, 4) and not has_note(lines, 136)
    print("self-test " + ("passed" if ok else f"FAILED: {found}"))
    return 0 if ok else 1


def main(argv):
    if "--self-test" in argv:
        return self_test()
    root = argv[1]
    limit = int(argv[argv.index("--limit") + 1]) if "--limit" in argv else 120
    if "--list" in argv:
        threshold = int(argv[argv.index("--list") + 1])
        rows = sorted((r for r in scan(root) if r[3] > threshold), key=lambda r: -r[3])
        for path, fn, first, length, note in rows:
            print(f"{length:5d}  {path}:{first}: {fn}{'  (noted)' if note else ''}")
        print(f"{len(rows)} functions over {threshold} lines")
        return 0
    baseline = set()
    if "--baseline" in argv:
        with open(argv[argv.index("--baseline") + 1], encoding="utf-8") as f:
            baseline = {line.split("#", 1)[0].strip() for line in f} - {""}
    offenders = [r for r in scan(root) if r[3] > limit and not r[4]]
    failed = 0
    for path, fn, first, length, _ in offenders:
        waiting = f"{path}: {fn}" in baseline
        failed += not waiting
        print(f"{path}:{first}: {fn}: {length} lines (over {limit}; "
              + ("in the baseline, waiting for its split)" if waiting else
                 f"split it into named steps or say why above it with '{NOTE}')"))
    stale = baseline - {f"{r[0]}: {r[1]}" for r in offenders}
    for entry in sorted(stale):
        print(f"{entry}: no longer over {limit} lines without a note: remove it from the baseline")
    print(f"check-function-length: {len(offenders)} functions over {limit} lines without a note, "
          f"{len(offenders) - failed} of them in the baseline; {len(stale)} stale baseline entries")
    return 1 if failed or stale else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
