#!/usr/bin/env python3
"""The files of a module that call each other in a loop, read from the build's object files.

    /usr/bin/python3 scripts/file_cycles.py build sim [--check]

For each object file of the module (build/CMakeFiles/perifem_<module>.dir/<module>/*.o) `nm`
gives the functions and data it defines and those it uses; file A calls file B when A uses a
symbol B defines. Prints every circle of files (a strongly connected set of two or more, each
with the names that tie it), or "no circles". With --check the exit status is 1 when there is a
circle (tests/regression/layers.sh runs it on sim/).
"""
import glob
import os
import subprocess
import sys


def symbols(obj):
    out = subprocess.run(["nm", "--defined-only", "-g", obj], capture_output=True, text=True, check=True).stdout
    defined = {line.split()[-1] for line in out.splitlines() if len(line.split()) == 3}
    out = subprocess.run(["nm", "-u", obj], capture_output=True, text=True, check=True).stdout
    used = {line.split()[-1] for line in out.splitlines() if line.split()}
    return defined, used


def circles(graph):
    """Tarjan's strongly connected components of size > 1."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph[v]:
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
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main():
    if len(sys.argv) < 3:
        print(__doc__.strip())
        return 2
    build, module = sys.argv[1], sys.argv[2]
    src = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", module)
    objs = sorted(o for o in glob.glob(os.path.join(build, "CMakeFiles", f"perifem_{module}.dir", module, "*.o"))
                  if os.path.exists(os.path.join(src, os.path.basename(o)[:-2])))  # (not a deleted file's)
    if not objs:
        print(f"file_cycles: no object files of {module}/ under {build} (build first)")
        return 2
    name = {o: f"{module}/" + os.path.basename(o)[:-2] for o in objs}
    syms = {name[o]: symbols(o) for o in objs}
    graph, ties = {}, {}
    for a, (_, used) in syms.items():
        graph[a] = set()
        for b, (defined, _) in syms.items():
            common = used & defined
            if a != b and common:
                graph[a].add(b)
                ties[(a, b)] = sorted(common)
    found = circles(graph)
    if not found:
        print(f"{module}/: no circles among {len(objs)} files")
    for comp in found:
        print(f"circle of {len(comp)} files: {', '.join(comp)}")
        for a in comp:
            for b in comp:
                if (a, b) in ties and b in graph[a]:
                    print(f"  {a} -> {b}: {', '.join(ties[(a, b)][:6])}")
    return 1 if found and "--check" in sys.argv else 0


if __name__ == "__main__":
    sys.exit(main())
