#!/usr/bin/env bash
# Every deck the documentation shows is a deck perifem accepts, and every command line of
# README.md, docs/user_guide.md and docs/deck_guide.md that calls perifem or a script in scripts/
# is exercised.
#
# Decks: every ```yaml (or ```yml) block of README.md, docs/*.md, docs/examples/*.md and
# docs/theory/*.md, at any indentation, is checked with `perifem --check` (which validates the
# deck and builds the model, and runs nothing): it must exit 0 and print no warning. A block is
# one of:
#  - a whole deck: a mapping with `bodies`, `time` and `materials` (or `include`). It is checked
#    as if it were a deck in inputs/ (so `../meshes/...` is found as from a shipped deck);
#  - a fragment, marked by an HTML comment on the line before the block (blank lines between
#    are allowed):
#        <!-- snippet: fragment of inputs/wave_in_bar.yaml -->
#        <!-- snippet: fragment of inputs/wave_in_bar.yaml at bodies.bar -->
#    The block is merged into that base deck (a path from the repository's top folder), at
#    its top level or at the mapping PATH names (as --set walks a deck: mapping keys, list
#    indices, list items by `name:`), and the result is checked beside the base deck. Merging:
#    each key of the block replaces the base's value, except that a mapping of mappings
#    (`materials`, `contact`) takes the block's keys one by one, and a list whose items all
#    have a `name:` (`bodies`, `rigid_surfaces`, named boundary conditions) replaces the base's
#    items of the same name and appends the others;
#  - a file the documentation has the reader write (the quick start's deck, an included part, a
#    points file): any fenced block marked `<!-- snippet: file NAME -->` is written as NAME, a
#    path from the top folder that is not in the repository (`inputs/materials.yaml` beside the
#    whole decks), before any deck is checked; it is checked itself when it is a whole deck.
# A yaml block that is none of these fails: nothing is skipped silently.
#
# Commands: each command of a ```sh (```bash, ```shell) block of README.md, docs/user_guide.md
# and docs/deck_guide.md that calls build/perifem, perifem or scripts/... (a line; one ending in a
# backslash goes on on the next) must be in the table COMMANDS below, which says how it is
# exercised: `check` runs it with --check added (a run's deck validated, cheaply); `help` runs
# the script with --help; `run` runs it as it is, from the top folder of the scratch tree (a
# perifem run must end with `health: ok` and print no warning; commands run in page order);
# `test NAME` names the test that runs it (which must exist); `ci` is a mode of
# scripts/setup.sh (the CI, .ci/run, runs `setup.sh --test`: the same installation and build).
# A command not in the table fails.
# usage: docs_snippets.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$(realpath "$1") scratch=$2 fail=0
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
"$PY" -c 'import yaml' 2> /dev/null || { echo "SKIP: python3 has no yaml module (Debian python3-yaml)"; exit 77; }
rm -rf "$scratch" && mkdir -p "$scratch/tree/inputs" "$scratch/tree/tests/data" "$scratch/out"
top=$(cd .. && pwd)
bad() { echo "FAIL: $*"; fail=1; }

# A copy of the tree in which decks can be written beside the shipped ones: inputs/ and
# tests/data/ hold links to their files, every other top-level entry is a link.
for e in "$top"/*; do
  case $(basename "$e") in inputs|tests|build) ;; *) ln -s "$e" "$scratch/tree/$(basename "$e")" ;; esac
done
for e in "$top"/inputs/*; do ln -s "$e" "$scratch/tree/inputs/"; done
for e in "$top"/tests/data/*; do ln -s "$e" "$scratch/tree/tests/data/"; done

# 1. Extract the blocks: write each deck to check into the tree, list them in decks.tsv
#    (deck path, where it comes from).
"$PY" - "$top" "$scratch/tree" > "$scratch/decks.tsv" 2> "$scratch/extract.err" <<'EOF'
import glob, os, re, sys
import yaml
top, tree = sys.argv[1], sys.argv[2]
files = [os.path.join(top, "README.md")] + sorted(
    glob.glob(os.path.join(top, "docs", "*.md")) + glob.glob(os.path.join(top, "docs", "examples", "*.md"))
    + glob.glob(os.path.join(top, "docs", "theory", "*.md")))
marker = re.compile(r"^<!--\s*snippet:\s*(.*?)\s*-->\s*$")
errors = []

def blocks(path):
    """(line, language, text, marker) of each fenced block of a page."""
    lines = open(path, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        m = re.match(r"^(\s*)```(\w*)\s*$", lines[i])
        if not m:
            i += 1
            continue
        indent, lang, start = len(m.group(1)), m.group(2).lower(), i
        lang = "yaml" if lang == "yml" else lang
        j = i + 1
        while j < len(lines) and not re.match(r"^\s*```\s*$", lines[j]):
            j += 1
        k = start - 1
        while k >= 0 and not lines[k].strip():
            k -= 1
        mk = marker.match(lines[k].strip()) if k >= 0 else None
        text = "\n".join(l[indent:] for l in lines[start + 1:j]) + "\n"
        yield start + 1, lang, text, mk.group(1) if mk else None
        i = j + 1

def key_of(node):
    return node.value if isinstance(node, yaml.ScalarNode) else None

def lookup(node, part):
    if isinstance(node, yaml.MappingNode):
        for k, v in node.value:
            if key_of(k) == part:
                return v
    elif isinstance(node, yaml.SequenceNode):
        if part.isdigit() and int(part) < len(node.value):
            return node.value[int(part)]
        for item in node.value:
            if isinstance(item, yaml.MappingNode) and name_of(item) == part:
                return item
    raise KeyError(part)

def name_of(item):
    for k, v in item.value:
        if key_of(k) == "name":
            return key_of(v)
    return None

def named_list(node):
    return (isinstance(node, yaml.SequenceNode) and node.value
            and all(isinstance(i, yaml.MappingNode) and name_of(i) is not None for i in node.value))

def put(mapping, key, value):
    for n, (k, v) in enumerate(mapping.value):
        if key_of(k) == key:
            mapping.value[n] = (k, value)
            return
    mapping.value.append((yaml.ScalarNode("tag:yaml.org,2002:str", key), value))

def merge(base, frag):
    """The block's keys into the base's mapping (the rules of the header)."""
    for k, v in frag.value:
        key = key_of(k)
        old = None
        try:
            old = lookup(base, key)
        except KeyError:
            pass
        if (isinstance(old, yaml.MappingNode) and isinstance(v, yaml.MappingNode)
                and all(isinstance(x, yaml.MappingNode) for _, x in old.value + v.value)
                and old.value and v.value):
            for kk, vv in v.value:
                put(old, key_of(kk), vv)
        elif named_list(old) and named_list(v):
            for item in v.value:
                for n, o in enumerate(old.value):
                    if name_of(o) == name_of(item):
                        old.value[n] = item
                        break
                else:
                    old.value.append(item)
        else:
            put(base, key, v)

def is_deck(node):
    keys = {key_of(k) for k, _ in node.value} if isinstance(node, yaml.MappingNode) else set()
    return {"bodies", "time"} <= keys and bool(keys & {"materials", "include"})

decks = []
for path in files:
    rel = os.path.relpath(path, top)
    for line, lang, text, mk in blocks(path):
        where = f"{rel}:{line}"
        if mk and mk.startswith("file "):
            name = mk[5:].strip()
            dest = os.path.join(tree, name)
            if os.path.lexists(dest) or os.path.lexists(os.path.join(top, name)):
                errors.append(f"{where}: file {name} is already in the repository")
            else:
                open(dest, "w").write(text)
            if lang == "yaml" and is_deck(yaml.compose(text)):
                decks.append((dest, where))
            continue
        if lang != "yaml":
            continue
        tag = re.sub(r"[^A-Za-z0-9]+", "_", rel[:-3]) + f"_{line}"
        try:
            node = yaml.compose(text)
        except yaml.YAMLError as e:
            errors.append(f"{where}: not YAML: {e}")
            continue
        if mk is None:
            if not is_deck(node):
                errors.append(f"{where}: a yaml block that is not a whole deck (materials, bodies, "
                              "time) and has no '<!-- snippet: fragment of BASE -->' marker")
                continue
            deck = os.path.join(tree, "inputs", f"snippet_{tag}.yaml")
            open(deck, "w").write(text)
        else:
            m = re.match(r"^fragment of (\S+)(?: at (\S+))?$", mk)
            if not m:
                errors.append(f"{where}: unknown snippet marker '{mk}'")
                continue
            base_rel, at = m.group(1), m.group(2)
            if not os.path.isfile(os.path.join(top, base_rel)):
                errors.append(f"{where}: base deck {base_rel} not found")
                continue
            base = yaml.compose(open(os.path.join(top, base_rel), encoding="utf-8").read())
            target = base
            try:
                for part in (at.split(".") if at else []):
                    target = lookup(target, part)
            except KeyError as e:
                errors.append(f"{where}: {base_rel} has no {at} ({e})")
                continue
            if not isinstance(node, yaml.MappingNode) or not isinstance(target, yaml.MappingNode):
                errors.append(f"{where}: the block and {base_rel} at {at or 'the top'} must be mappings")
                continue
            merge(target, node)
            deck = os.path.join(tree, os.path.dirname(base_rel), f"snippet_{tag}.yaml")
            open(deck, "w").write(yaml.serialize(base, width=1000))
        decks.append((deck, where))
for deck, where in decks:
    print(f"{deck}\t{where}")
for e in errors:
    print(e, file=sys.stderr)
sys.exit(1 if errors else 0)
EOF
[ $? -eq 0 ] || bad "the documentation's yaml blocks:"
sed 's/^/  /' "$scratch/extract.err"

n=0
while IFS=$'\t' read -r deck where; do
  n=$((n + 1))
  OMP_NUM_THREADS=1 "$exe" --check --output-dir "$scratch/out" "$deck" > "$scratch/check_$n.log" 2>&1
  rc=$?
  if [ $rc -ne 0 ]; then
    bad "$where: perifem --check exited $rc (deck $deck):"
    sed 's/^/  /' "$scratch/check_$n.log" | head -20
  elif grep -q 'warning' "$scratch/check_$n.log"; then
    bad "$where: perifem --check warns (deck $deck): $(grep -m1 warning "$scratch/check_$n.log")"
  fi
done < "$scratch/decks.tsv"

# 2. The command lines. Key: the command as written (without its comment); value: how it is
#    exercised.
declare -A COMMANDS=(
  ["bash scripts/setup.sh --example"]="test slow_panel_outcomes"
  ["bash scripts/setup.sh --test"]="ci"
  ["bash scripts/setup.sh"]="ci"
  ["build/perifem inputs/disk_impact_elastic.yaml"]="check"
  ["mpirun -np 2 build/perifem inputs/disk_impact_elastic.yaml"]="test mpi_digests"
  ["build/perifem --check DECK.yaml"]="test check_report"
  ["build/perifem plate.yaml"]="run"
  ["/usr/bin/python3 scripts/plot_history.py plate.h5 --out plots"]="run"
  ["xvfb-run -a pvbatch scripts/render_fields.py run/panel_impact.e eqps.png --field eqps --view back --clip-y 0"]="test slow_render_fields"
  ["xvfb-run -a pvbatch scripts/render_fields.py run.e vz.png --field velocity_z --time 2e-5 --clip-y 0 --view front"]="test slow_render_fields"
)
"$PY" - "$top" > "$scratch/commands.txt" <<'EOF'
import os, re, sys
top = sys.argv[1]
for rel in ("README.md", "docs/user_guide.md", "docs/deck_guide.md"):
    inside, pending = False, ""
    for n, line in enumerate(open(os.path.join(top, rel), encoding="utf-8"), 1):
        if re.match(r"^\s*```(sh|bash|shell)\s*$", line):
            inside = True
        elif re.match(r"^\s*```", line):
            inside = False
        elif inside:
            if pending:
                line, pending = pending + " " + line.strip(), ""
            if line.rstrip("\n").endswith("\\"):
                pending = line.rstrip("\n")[:-1].strip()
                continue
            cmd = re.sub(r"\s+#.*$", "", line.rstrip("\n")).strip()
            if re.search(r"(^|[\s/])perifem(\s|$)|scripts/", cmd):
                print(f"{rel}:{n}\t{cmd}")
EOF
ncmd=0
while IFS=$'\t' read -r where cmd; do
  ncmd=$((ncmd + 1))
  how=${COMMANDS[$cmd]-}
  [ -n "$how" ] || { bad "$where: '$cmd' calls perifem or a script but the table of this test does not say how it is exercised"; continue; }
  # the command with build/perifem as the perifem under test, run from a scratch copy of the top folder
  words=($cmd)
  for i in "${!words[@]}"; do [ "${words[$i]}" = build/perifem ] && words[$i]=$exe; done
  case $how in
    ci) # .ci/run runs setup.sh --test: the same installation and build as the other modes
      grep -q '^bash scripts/setup.sh --test' ../.ci/run || bad "$where: '$cmd': .ci/run does not run scripts/setup.sh --test" ;;
    test\ *)
      t=${how#test }
      [ -f "regression/$t.sh" ] || [ -f "verification/$t.c" ] || bad "$where: '$cmd' is said to be run by $t, which does not exist" ;;
    check|run|help)
      [ $how = check ] && words+=(--check)
      if [ $how = help ]; then
        i=0; while [[ ${words[$i]} != scripts/* ]]; do i=$((i + 1)); done
        words=("${words[@]:0:$((i + 1))}" --help)
      fi
      (cd "$scratch/tree" && OMP_NUM_THREADS=1 "${words[@]}") > "$scratch/cmd_$ncmd.log" 2>&1
      rc=$?
      [ $rc -eq 0 ] || { bad "$where: '$cmd' ($how) exited $rc:"; sed 's/^/  /' "$scratch/cmd_$ncmd.log" | head -20; }
      if [ $how = run ] && [[ " ${words[*]} " == *" $exe "* ]] && [[ " ${words[*]} " != *" --check "* ]]; then
        grep -q '^health: ok$' "$scratch/cmd_$ncmd.log" || bad "$where: '$cmd' does not end with 'health: ok'"
        ! grep -q 'warning' "$scratch/cmd_$ncmd.log" || bad "$where: '$cmd' printed a warning: $(grep -m1 warning "$scratch/cmd_$ncmd.log")"
      fi ;;
    *) bad "$where: unknown way '$how'" ;;
  esac
done < "$scratch/commands.txt"

[ $fail -eq 0 ] && echo "docs snippets: $(wc -l < "$scratch/decks.tsv") yaml blocks checked with perifem --check, $ncmd command lines exercised"
exit $fail
