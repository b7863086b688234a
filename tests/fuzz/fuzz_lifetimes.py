#!/usr/bin/env python3
"""API-lifetime fuzzing of the Python package ("Nothing silently wrong"): each case is a seeded
sequence of calls on the package - simulations created, stepped, run, checked, closed, dropped
and collected; field views and copies taken and read after their simulation is closed or gone;
checkpoints written to a fresh path, to the deck or to a folder; perifem.finalize() in the
middle - run in a fresh interpreter. A case passes when the interpreter ends with status 0: every
call either works or raises perifem.PerifemError, TypeError or ValueError (caught and counted),
never a crash, a hang (--timeout seconds) or another exception; and the deck is unchanged.

  python3 tests/fuzz/fuzz_lifetimes.py DECK SCRATCH [--seed N] [--cases N] [--budget S]
(the package importable: PYTHONPATH, PERIFEM_LIBRARY, as tests/regression/python_api.sh sets them)
"""
import argparse
import hashlib
import os
import random
import re
import subprocess
import sys
import time

OPS = ["new", "new", "step", "step", "run", "check", "close", "drop", "gc", "view", "view", "copy",
       "read", "read", "checkpoint_new", "checkpoint_deck", "checkpoint_folder", "history", "digest",
       "finalize"]
CRASH = re.compile(r"Segmentation|Abort|core dumped|Bus error|Fatal Python error|double free|malloc\(\): ")

# the interpreter of one case: OPS names, one a line, on standard input
RUNNER = r'''
import gc, sys
import numpy as np
import perifem
deck = sys.argv[1]
sims, views, ok, refused = [], [], 0, 0
def pick(seq, k):
    return seq[k % len(seq)] if seq else None
for n, line in enumerate(sys.stdin):
    op, k = line.split()
    k = int(k)
    try:
        if op == "new":
            sims.append(perifem.Simulation(deck, overrides=["time.steps=6"], output=False))
        elif op == "step" and sims:
            pick(sims, k).step(1 + k % 3)
        elif op == "run" and sims:
            pick(sims, k).run()
        elif op == "check" and sims:
            pick(sims, k).check()
        elif op == "close" and sims:
            pick(sims, k).close()
        elif op == "drop" and sims:
            sims.pop(k % len(sims))
        elif op == "gc":
            gc.collect()
        elif op == "view" and sims:
            views.append(pick(sims, k).field_view(0, "displacement"))
        elif op == "copy" and sims:
            views.append(pick(sims, k).field(0, "velocity"))
        elif op == "read" and views:
            float(np.sum(pick(views, k)))
        elif op == "checkpoint_new" and sims:
            pick(sims, k).checkpoint("ck_%d.h5" % n)
        elif op == "checkpoint_deck" and sims:
            pick(sims, k).checkpoint(deck)
        elif op == "checkpoint_folder" and sims:
            pick(sims, k).checkpoint(".")
        elif op == "history" and sims:
            pick(sims, k).history_row()
        elif op == "digest" and sims:
            pick(sims, k).digest()
        elif op == "finalize":
            perifem.finalize()
        ok += 1
    except (perifem.PerifemError, TypeError, ValueError):
        refused += 1
print("calls %d, refused %d" % (ok, refused))
'''


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("deck")
    ap.add_argument("scratch")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", type=int, default=40)
    ap.add_argument("--budget", type=float, default=30.0)
    ap.add_argument("--length", type=int, default=14)
    ap.add_argument("--timeout", type=float, default=60.0)
    a = ap.parse_args()
    rng = random.Random(a.seed)
    os.makedirs(a.scratch, exist_ok=True)
    start, failures, n = time.time(), 0, 0
    while n < a.cases and time.time() - start < a.budget:
        n += 1
        case_dir = os.path.join(a.scratch, "case%03d" % n)
        os.makedirs(case_dir)
        deck = os.path.join(case_dir, "deck.yaml")
        with open(a.deck) as f, open(deck, "w") as g:
            g.write(f.read())
        before = digest(deck)
        ops = [(rng.choice(OPS), rng.randrange(1000)) for _ in range(a.length)]
        text = "".join("%s %d\n" % o for o in ops)
        try:
            p = subprocess.run([sys.executable, "-c", RUNNER, "deck.yaml"], input=text, cwd=case_dir,
                               capture_output=True, text=True, timeout=a.timeout)
            problem = ""
            if p.returncode != 0 or CRASH.search(p.stderr):
                problem = "status %d: %s" % (p.returncode, (p.stderr.strip().splitlines() or [""])[-1][:300])
        except subprocess.TimeoutExpired:
            problem = "hung (over %g s)" % a.timeout
        if not problem and digest(deck) != before:
            problem = "the deck changed"
        if problem:
            failures += 1
            print("FAIL case %d (%s): %s" % (n, " ".join(o for o, _ in ops), problem))
    print("fuzz_lifetimes: seed %d, %d cases, %d failures, %.0f s" % (a.seed, n, failures, time.time() - start))
    return 1 if failures or n == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
