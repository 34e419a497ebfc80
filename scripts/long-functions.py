#!/usr/bin/env python3
"""Lists functions longer than a limit (default 150 lines) in the C++ sources, tests and benchmarks.

Usage: scripts/long-functions.py [--limit N] [FOLDER ...]   (default: sh prt scene bake radiosity relight
report cli, and tests bench fuzz examples fixtures). A function is a top-level or namespace-level
brace block whose opening line looks like a definition (a Catch2 TEST_CASE counts as one);
lambdas count as part of the function that holds them. Exits 1 when it lists any (ctest runs it
as `long_functions`).
"""
import argparse
import pathlib
import re

DEFINITION = re.compile(r"[\w:~<>,\s\*&]+\([^;]*\)\s*(const)?\s*(noexcept)?\s*(->\s*[\w:<>]+)?\s*\{?\s*$")


def functions(path):
    lines = path.read_text(errors="replace").splitlines()
    depth, start, name, scopes = 0, None, None, []
    for i, line in enumerate(lines):
        code = re.sub(r"//.*", "", line)
        code = re.sub(r'"([^"\\]|\\.)*"', '""', code)
        code = re.sub(r"'([^'\\]|\\.)'", "''", code)  # '{' and '}' open and close nothing
        opens, closes = code.count("{"), code.count("}")
        if start is None and opens and not re.match(r"\s*(namespace|struct|class|enum|union|extern)\b", code):
            head = " ".join(lines[max(0, i - 3): i + 1])
            if "(" in head and all(s == "ns" for s in scopes):
                start, name, body_depth = i, code.strip()[:70], len(scopes)
        for ch in code:
            if ch == "{":
                scopes.append("ns" if re.match(r"\s*(namespace|extern)\b", code) else "x")
            elif ch == "}" and scopes:
                scopes.pop()
                if start is not None and len(scopes) == body_depth:
                    yield start + 1, i - start + 1, name
                    start = None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--limit", type=int, default=150)
    ap.add_argument("folders", nargs="*", default=["sh", "prt", "scene", "bake", "radiosity", "relight", "report", "cli",
                                                   "tests", "bench", "fuzz", "examples", "fixtures"])
    args = ap.parse_args()
    root = pathlib.Path(__file__).resolve().parent.parent
    found = []
    for folder in args.folders:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix in (".cpp", ".h") and path.is_file():
                for line, length, name in functions(path):
                    if length > args.limit:
                        found.append((length, f"{path.relative_to(root)}:{line}", name))
    for length, where, name in sorted(found, reverse=True):
        print(f"{length:5d}  {where}  {name}")
    return 1 if found else 0


if __name__ == "__main__":
    raise SystemExit(main())
