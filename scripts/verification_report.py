#!/usr/bin/env python3
"""Keep docs/verification.md's measured values equal to what the tests measure.

The document is written by hand; each value a test measures is marked in place:

    <!--m test_wave.phase_speed %.2f-->3521.17<!--/m-->

`test_wave` is the test's name (the ctest name without its folder), `phase_speed` the key it
records with pf_test_measure (tests/common/test_common.h) or pf_measure (tests/common/measure.sh),
`%.2f` the printf format the value is printed with. Options after the format:
  tol=X   the value may differ from the measurement by X (absolute) without being stale,
          instead of one unit of its last printed digit: for values that differ between
          machines beyond the printed digits (round-off, AVX-512 or not, valgrind);
  rel=X   the same, relative to the measurement;
  x=S     print S times the measured value (x=100 prints a fraction as a percentage);
  u       print a negative value with the typographic minus (U+2212), as the prose does.
A format with a quote flag (%'d, %'.0f) groups thousands with commas.

Run after ctest (whose tests write build/tests/measured/<test>.tsv):
    python3 scripts/verification_report.py            rewrite the marked values and the stamp
    python3 scripts/verification_report.py --check    change nothing; exit 1 listing
        - marked values that differ from the measurement by more than one unit of their last
          printed digit (or their tol/rel; a printed 0 must be exactly 0),
        - markers of a test that ran whose key it did not record,
        - keys a test recorded that no marker quotes,
        - markers with no measurement at all (their test neither ran nor has a recorded value),
        - works cited by author and year that have no entry in docs/bibliography.md.
Tests that did not run (the slow ones in a default run) are compared with their last recorded
values, docs/verification_measured.tsv (test.key, value, unit, commit, date), which a rewrite
refreshes with every measurement of the run.
"""
import argparse
import datetime
import math
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MARK = re.compile(r"<!--m ([A-Za-z0-9_.\-]+) ([^>]*?)-->(.*?)<!--/m-->")
STAMP = re.compile(r"<!--stamp-->.*?<!--/stamp-->", re.S)
MINUS = "\u2212"


def read_run(folder):
    """{test: {key: (value, unit)}} from the run's <test>.tsv files (each test that ran has one)."""
    run = {}
    if not os.path.isdir(folder):
        return run
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".tsv"):
            continue
        values = run.setdefault(name[:-4], {})
        with open(os.path.join(folder, name)) as f:
            for n, line in enumerate(f, 1):
                parts = line.rstrip("\n").split("\t")
                if len(parts) < 2:
                    sys.exit(f"{folder}/{name}:{n}: expected 'key<TAB>value<TAB>unit'")
                try:
                    value = float(parts[1])
                except ValueError:
                    value = math.nan  # reported as a problem where a marker quotes it
                values[parts[0]] = (value, parts[2] if len(parts) > 2 else "")
    return run


def read_recorded(path):
    """{test.key: (value, unit, commit, date)} from the committed record."""
    rec = {}
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                if line.startswith("#") or not line.strip():
                    continue
                key, value, unit, commit, date = line.rstrip("\n").split("\t")
                rec[key] = (float(value), unit, commit, date)
    return rec


def write_recorded(path, rec):
    with open(path, "w") as f:
        f.write("# The last recorded measurement of every value docs/verification.md quotes\n"
                "# (scripts/verification_report.py): test.key, value, unit, commit, date.\n")
        for key in sorted(rec):
            value, unit, commit, date = rec[key]
            f.write(f"{key}\t{value!r}\t{unit}\t{commit}\t{date}\n")


def parse_options(spec):
    words = spec.split()
    if not words or not words[0].startswith("%"):
        raise ValueError(f"marker format '{spec}' does not start with a printf format")
    opts = {"fmt": words[0], "tol": 0.0, "rel": 0.0, "x": 1.0, "u": False}
    for w in words[1:]:
        if w == "u":
            opts["u"] = True
        elif "=" in w and w.split("=")[0] in ("tol", "rel", "x"):
            opts[w.split("=")[0]] = float(w.split("=", 1)[1])
        else:
            raise ValueError(f"unknown marker option '{w}'")
    return opts


def format_value(value, opts):
    value *= opts["x"]
    fmt = opts["fmt"]
    grouped = "'" in fmt
    fmt = fmt.replace("'", "")
    if fmt.endswith("d"):
        value = int(round(value))
    text = "0" if value == 0 and fmt[-1] in "eEgG" else fmt % value  # an exact zero as 0
    if grouped:
        sign = "-" if text.startswith("-") else ""
        whole, _, frac = text.lstrip("-").partition(".")
        text = sign + f"{int(whole):,}" + ("." + frac if frac else "")
    text = re.sub(r"e([+-])0*(\d)", lambda m: "e" + m.group(1).replace("+", "") + m.group(2), text)  # 1e-4, 2e22
    if opts["u"] and text.startswith("-"):
        text = MINUS + text[1:]
    return text


def printed_number(text):
    """The number a printed value stands for, and one unit of its last printed digit."""
    t = text.replace(MINUS, "-").replace(",", "").strip()
    value = float(t)
    mant, _, exp = t.lower().partition("e")
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    return value, 10.0 ** (int(exp or 0) - decimals)


def stale(printed, measured, opts):
    """None when the printed value stands for the measurement, else the difference."""
    try:
        value, quantum = printed_number(printed)
    except ValueError:
        return "not a number"
    want = measured * opts["x"]
    if opts["tol"] or opts["rel"]:
        allowed = max(opts["tol"], opts["rel"] * abs(want))
    else:
        allowed = quantum if value != 0 else 0.0  # a printed 0 means exactly 0
    allowed *= 1 + 1e-12
    diff = abs(value - want)
    return None if diff <= allowed else f"differs by {diff:.3g} (allowed {allowed:.3g})"


def git_commit():
    try:
        head = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return head + ("+edits" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


CITE = re.compile(r"\b((?:[A-Z][A-Za-z\u00C0-\u017F'\-]+)(?:(?:,| &| and) [A-Z][A-Za-z\u00C0-\u017F'\-]+)*"
                  r"(?: et al\.)?)(?:'s)?,? \(?((?:1[89]|20)\d\d)[a-z]?\b(?!-\d)")
# Words before a year that are not authors (dates, versions, products).
NOT_AUTHORS = {"Debian", "Release", "November", "CalculiX", "Benchmarks", "Manual", "SIAM", "MS",
               "Abaqus", "Ubuntu", "Open", "MPI", "HDF", "Exodus", "Table", "Figure", "Fig",
               "Section", "ASME", "IMECE", "ISO", "ASTM", "C", "GCC", "Python", "Intel", "AMD"}


def bibliography_entries(path):
    """(surname words, year) of every entry: its bold short citation, e.g. **Silling & Askari 2005**."""
    entries = []
    with open(path) as f:
        for m in re.finditer(r"\*\*([^*]+?) ((?:1[89]|20)\d\d)[a-z]?\*\*", f.read()):
            entries.append((set(re.findall(r"[A-Z][A-Za-z\u00C0-\u017F'\-]+", m.group(1))), m.group(2)))
    return entries


def uncited(doc_text, bib_path):
    """Author-year citations of the document with no bibliography entry of that author and year."""
    entries = bibliography_entries(bib_path)
    missing = set()
    for m in CITE.finditer(doc_text):
        names = [n for n in re.findall(r"[A-Z][A-Za-z\u00C0-\u017F'\-]+", m.group(1)) if n not in NOT_AUTHORS]
        if not names:
            continue
        year = m.group(2)
        first = names[0]
        if not any(first in words and year == y for words, y in entries):
            missing.add(f"{m.group(1)} {year}")
    return sorted(missing)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--check", action="store_true", help="change nothing; fail on stale values")
    ap.add_argument("--measured", default=os.path.join(ROOT, "build", "tests", "measured"),
                    help="the run's measurement folder (default build/tests/measured)")
    ap.add_argument("--doc", default=os.path.join(ROOT, "docs", "verification.md"))
    ap.add_argument("--record", default=os.path.join(ROOT, "docs", "verification_measured.tsv"))
    ap.add_argument("--bibliography", default=os.path.join(ROOT, "docs", "bibliography.md"))
    args = ap.parse_args()

    run = read_run(args.measured)
    recorded = read_recorded(args.record)
    with open(args.doc) as f:
        doc = f.read()
    problems, used, changed = [], set(), 0
    commit = git_commit()
    today = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")

    def measurement(key):
        test, _, name = key.partition(".")
        if test in run:
            return run[test].get(name, (None, ""))[0], "this run"
        if key in recorded:
            return recorded[key][0], f"recorded at {recorded[key][2]} on {recorded[key][3]}"
        return None, "no run and no record"

    def replace(m):
        nonlocal changed
        key, spec, printed = m.group(1), m.group(2), m.group(3)
        if m.start() > 0 and doc[m.start() - 1] == "`":
            return m.group(0)  # an example in inline code, not a marker
        line = doc.count("\n", 0, m.start()) + 1
        try:
            opts = parse_options(spec)
        except ValueError as e:
            problems.append(f"{args.doc}:{line}: {key}: {e}")
            return m.group(0)
        used.add(key)
        value, source = measurement(key)
        if value is None:
            test = key.partition(".")[0]
            why = f"test {test} ran but did not record it" if test in run else source
            problems.append(f"{args.doc}:{line}: {key}: no measurement ({why})")
            return m.group(0)
        if math.isnan(value):
            problems.append(f"{args.doc}:{line}: {key}: the measurement is not a number")
            return m.group(0)
        if args.check:
            d = stale(printed, value, opts)
            if d:
                problems.append(f"{args.doc}:{line}: {key}: printed {printed}, measured "
                                f"{format_value(value, opts)} ({source}): {d}")
            return m.group(0)
        text = format_value(value, opts)
        if text != printed:
            changed += 1
        return f"<!--m {key} {spec}-->{text}<!--/m-->"

    new_doc = MARK.sub(replace, doc)
    for test, values in sorted(run.items()):
        for name in sorted(values):
            if f"{test}.{name}" not in used:
                problems.append(f"{args.measured}/{test}.tsv: {name}: recorded, but no marker "
                                f"<!--m {test}.{name} ...--> quotes it")
    for cite in uncited(doc, args.bibliography):
        problems.append(f"{args.doc}: cites '{cite}', which has no entry in {args.bibliography}")

    if args.check:
        for p in problems:
            print(p)
        n_runs = sum(1 for k in used if k.partition(".")[0] in run)
        print(f"{len(used)} marked values ({n_runs} from this run's {len(run)} tests' measurements, "
              f"the rest from {os.path.basename(args.record)}): "
              + (f"{len(problems)} problems" if problems else "all current"))
        return 1 if problems else 0

    stamp = (f"<!--stamp-->The marked values were last refreshed from a run of commit `{commit}` "
             f"on {today} ({len(run)} tests ran; the others' values are their last recorded "
             f"ones, `docs/verification_measured.tsv`).<!--/stamp-->")
    new_doc = STAMP.sub(lambda _: stamp, new_doc, count=1)
    with open(args.doc, "w") as f:
        f.write(new_doc)
    for test, values in run.items():
        for name, (value, unit) in values.items():
            recorded[f"{test}.{name}"] = (value, unit, commit, today)
    write_recorded(args.record, recorded)
    for p in problems:
        print(p)
    print(f"{changed} of {len(used)} marked values changed; {len(run)} tests' measurements recorded")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
