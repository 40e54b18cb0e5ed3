#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Which source files of src/ call functions defined in which others.

Reads the symbol tables of the objects a build made (nm: a file's defined
global functions, "T", and the names it uses but does not define, "U"), maps
every used name to the file that defines it, and prints, for each .c under
src/, the functions it calls in other files. Pairs of files that call each
other and longer cycles between files are listed at the end.

    tools/file_calls.py BUILD_DIR [--under src/lang] [--cycles-only]
        [--fail-on-cycles]

The exit status is 1 with --fail-on-cycles when a cycle lies under the given
directory (an object is named after its source, as CMake does:
CMakeFiles/TARGET.dir/src/lang/check.c.o).
"""
import argparse
import os
import subprocess
import sys


SOURCE_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def objects(build):
    """Source path (src/...) -> one object built from it, among the targets of the
    top-level CMakeLists.txt (BUILD/CMakeFiles/TARGET.dir/src/...)."""
    found = {}
    top = os.path.join(build, "CMakeFiles")
    for target in sorted(os.listdir(top)) if os.path.isdir(top) else []:
        src = os.path.join(top, target, "src")
        if not target.endswith(".dir") or not os.path.isdir(src):
            continue
        for root, _dirs, files in os.walk(src):
            for name in sorted(files):
                if name.endswith(".c.o"):
                    path = os.path.join(root, name)
                    source = os.path.relpath(path, os.path.join(top, target))[: -len(".o")]
                    # an object left by a source file since removed or renamed is not read
                    if os.path.exists(os.path.join(SOURCE_ROOT, source)):
                        found.setdefault(source, path)
    return found


def symbols(objs):
    """Source -> (its defined global functions, the names it uses undefined), from one
    run of nm over every object (nm -A: each line begins with the object's path)."""
    source_of = {obj: source for source, obj in objs.items()}
    out = subprocess.run(["nm", "-A"] + sorted(source_of), check=True,
                         capture_output=True, text=True).stdout
    table = {source: (set(), set()) for source in objs}
    for line in out.splitlines():
        path, _, rest = line.partition(":")
        parts = rest.split()
        defined, used = table[source_of[path]]
        if len(parts) == 3 and parts[1] == "T":
            defined.add(parts[2])
        elif len(parts) == 2 and parts[0] == "U":
            used.add(parts[1])
    return table


def cycles(graph):
    """Strongly connected components of more than one file (Tarjan)."""
    index, low, stack, on, comps = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(comps)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("build")
    ap.add_argument("--under", default="src",
                    help="report files and cycles under this directory")
    ap.add_argument("--cycles-only", action="store_true")
    ap.add_argument("--fail-on-cycles", action="store_true")
    args = ap.parse_args()
    under = args.under.rstrip("/") + "/"

    objs = objects(args.build)
    if not objs:
        sys.exit(f"{args.build}: no object built from src/ (build first)")
    defs, uses = {}, {}
    for source, (defined, used) in sorted(symbols(objs).items()):
        uses[source] = used
        for name in defined:
            defs.setdefault(name, source)

    calls = {}
    for source, used in uses.items():
        for name in used:
            target = defs.get(name)
            if target and target != source:
                calls.setdefault(source, {}).setdefault(target, set()).add(name)
    graph = {s: set(t) for s, t in calls.items()}

    if not args.cycles_only:
        for source in sorted(calls):
            if not source.startswith(under):
                continue
            print(source)
            for target in sorted(calls[source]):
                print(f"  {target}: {', '.join(sorted(calls[source][target]))}")

    found = [c for c in cycles(graph) if any(f.startswith(under) for f in c)]
    pairs = sorted((a, b) for a in graph for b in graph[a]
                   if a < b and a in graph.get(b, ()) and a.startswith(under))
    print(f"pairs of files under {under} that call each other: {len(pairs)}")
    for a, b in pairs:
        print(f"  {a} <-> {b}: {', '.join(sorted(calls[a][b]))} / "
              f"{', '.join(sorted(calls[b][a]))}")
    print(f"cycles between files under {under}: {len(found)}")
    for comp in found:
        print("  " + " -> ".join(comp))
    if args.fail_on_cycles and found:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
