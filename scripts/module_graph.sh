#!/usr/bin/env bash
# The modules and what each links, drawn from the build's own link graph (CMake's --graphviz):
# one box per module library, an arrow from a module to each module it links (transitive
# arrows removed). Writes OUT (default docs/architecture_modules.png); needs graphviz (dot, tred).
#   bash scripts/module_graph.sh [OUT.png]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-docs/architecture_modules.png}
work=$(mktemp -d /tmp/perifem_graph.XXXXXX)
trap 'rm -rf "$work"' EXIT
cmake -S . -B "$work/build" -DPERIFEM_OPENMP_CHECK=OFF --graphviz="$work/all.dot" >/dev/null
python3 - "$work/all.dot" > "$work/modules.dot" <<'PY'
import re, sys
label, edges = {}, []
for line in open(sys.argv[1]):
    m = re.match(r'\s*"(node\d+)" \[ label = "([^"]+)"', line)
    if m: label[m.group(1)] = m.group(2)
    m = re.match(r'\s*"(node\d+)" -> "(node\d+)"', line)
    if m: edges.append((m.group(1), m.group(2)))
mod = lambda n: label.get(n, "")[len("perifem_"):] if re.fullmatch(r"perifem_[a-z]+", label.get(n, "")) and label[n] != "perifem_lib" else None
print('digraph modules {\n  rankdir=TB; node [shape=box, style="rounded,filled", fillcolor="#eef3fa", fontname="Helvetica"];')
for a, b in sorted(set((mod(a), mod(b)) for a, b in edges if mod(a) and mod(b))):
    print(f'  "{a}/" -> "{b}/";')
print("}")
PY
tred "$work/modules.dot" | dot -Tpng -Gdpi=110 -o "$out"
echo "wrote $out"
