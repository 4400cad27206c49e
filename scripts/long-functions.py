#!/usr/bin/env python3
"""Lists functions in Module/ longer than a limit (default 80 lines).

  scripts/long-functions.py [--limit 80] [DIR]

Counts from a function body's opening brace at column 0 (VTK's Allman style) to
its closing brace at column 0; class, struct, enum and namespace bodies are not
functions. Issue 12 asks that nothing in Module/ be over about 80 lines. Prints
one line per long function and a count; exits 0 either way (it measures).
"""
import argparse
import pathlib
import re

BODY_NOT_A_FUNCTION = re.compile(r"^(namespace|struct|class|enum|union|extern)\b|\bclass\b.*:|:\s*public\b")


def long_functions(path, limit):
    lines = path.read_text(errors="replace").split("\n")
    start, name = None, ""
    for i, line in enumerate(lines):
        if line == "{" and start is None and i > 0:
            previous = lines[i - 1]
            if previous.strip() and not BODY_NOT_A_FUNCTION.search(previous):
                start, name = i, previous.strip()
        elif line.startswith("}") and start is not None:
            if i - start + 1 > limit:
                yield i - start + 1, name
            start = None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--limit", type=int, default=80)
    parser.add_argument("directory", nargs="?", default="Module")
    args = parser.parse_args()
    found = []
    for path in sorted(pathlib.Path(args.directory).rglob("*")):
        if path.suffix in (".cxx", ".h"):
            found += [(n, str(path), name) for n, name in long_functions(path, args.limit)]
    for n, path, name in sorted(found, reverse=True):
        print(f"{n:5d}  {path}  {name[:90]}")
    print(f"{len(found)} function(s) over {args.limit} lines")


if __name__ == "__main__":
    main()
