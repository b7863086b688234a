#!/usr/bin/env python3
"""Derived-number fuzzing of the command line ("Nothing silently wrong"): each case is one of the
small decks of tests/fuzz/decks with one number replaced by a value that passes YAML but not
physics - huge, negative, zero, tiny, not finite, beyond a long - or one expression (an initial
velocity, a horizon, a blending weight, a prescribed motion) replaced by one that is not finite
somewhere. The step counts, dt, final time, moduli, densities, coordinates, spacings and
horizons are all numbers of these decks. perifem runs each case, and the case passes when it
ends with

  exit 0 (the value was harmless), or
  exit 2 and a message naming a deck key ("key '...'"), or
  exit 1 and a "perifem error" message (a run that failed and said why);

never a signal, a crash message, a hang (--timeout seconds) or an exit 1 without a message.
The cases come from a seeded generator (the same seed, the same cases); the default run stops
after --budget seconds (50) or --cases cases (60), whichever comes first.

  python3 tests/fuzz/fuzz_numbers.py PERIFEM SCRATCH [--seed N] [--cases N] [--budget S]
"""
import argparse
import os
import random
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
DECKS = ["pd", "fe", "coupled", "contact"]
NUMBERS = ["0", "-1", "-0.5", "1e300", "-1e300", "1e-300", "1e-30", ".nan", ".inf", "-.inf", "1e19",
           "9223372036854775807", "1e13", "4.5e15", "2147483648", "1e8"]
EXPRESSIONS = ["1/0", "0/0", "sqrt(-1)", "1e308*1e308", "x*1e300", "-1e300", "log(0)", "x < 0.002 ? 1/0 : 0",
               "1e-320"]
CRASH = re.compile(r"Segmentation|Abort|core dumped|Bus error|Floating point exception|Illegal instruction|"
                   r"AddressSanitizer|runtime error:|stack smashing|double free|malloc\(\): ")
# a number that is a YAML value: after ': ', '[', ', ' or '- ' (not in a comment, a name or Pamgen's
# text, whose numbers are guarded separately); a quoted expression
NUM = re.compile(r"(?<=[:\[,] )-?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?=[\],}\s])")
EXPR = re.compile(r'"[^"\n]*"')


def sites(text):
    out = []
    for m in NUM.finditer(text):
        line = text[text.rfind("\n", 0, m.start()) + 1:m.start()]
        if "#" not in line and "=" not in line:
            out.append(("number", m.start(), m.end()))
    for m in EXPR.finditer(text):
        line = text[text.rfind("\n", 0, m.start()) + 1:m.start()]
        if "#" not in line and "title" not in line:
            out.append(("expression", m.start(), m.end()))
    return out


def cases(seed):
    rng = random.Random(seed)
    texts = {}
    for name in DECKS:
        with open(os.path.join(HERE, "decks", name + ".yaml")) as f:
            text = f.read()
        # no checkpoints: the cases test the set-up and the run, not the restart
        texts[name] = re.sub(r"(?m)^restart:.*\n", "", text)
    while True:
        name = rng.choice(DECKS)
        text = texts[name]
        kind, a, b = rng.choice(sites(text))
        value = rng.choice(NUMBERS) if kind == "number" else '"%s"' % rng.choice(EXPRESSIONS)
        yield name, text[:a] + value + text[b:], "%s: %s -> %s (line %d)" % (
            name, text[a:b], value, text.count("\n", 0, a) + 1)


def verdict(status, err):
    if status is None:
        return "hang"
    if status < 0 or status >= 128:
        return "signal %d" % (-status if status < 0 else status - 128)
    if CRASH.search(err):
        return "crash message"
    if status == 0:
        return None
    if status == 2:
        return None if "key '" in err else "exit 2 without a message naming a key"
    if status == 1:
        return None if "perifem error" in err else "exit 1 without a message"
    return "exit %d" % status


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("perifem")
    ap.add_argument("scratch")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", type=int, default=60)
    ap.add_argument("--budget", type=float, default=50.0)
    ap.add_argument("--timeout", type=float, default=30.0)
    o = ap.parse_args()
    os.makedirs(o.scratch, exist_ok=True)
    env = dict(os.environ, OMPI_MCA_rmaps_base_oversubscribe="1")
    t0, done, failed, statuses = time.time(), 0, 0, {}
    for name, text, what in cases(o.seed):
        if done >= o.cases or time.time() - t0 > o.budget:
            break
        deck = os.path.join(o.scratch, "case%03d.yaml" % done)
        with open(deck, "w") as f:
            f.write(text)
        out = os.path.join(o.scratch, "out%03d" % done)
        try:
            p = subprocess.run([o.perifem, "--quiet", "--output-dir", out, deck], capture_output=True,
                               timeout=o.timeout, env=env)
            status, err = p.returncode, p.stderr.decode(errors="replace")
        except subprocess.TimeoutExpired:
            status, err = None, ""
        bad = verdict(status, err)
        statuses[status] = statuses.get(status, 0) + 1
        if bad:
            failed += 1
            print("FAIL case %d (%s): %s; stderr: %s" % (done, what, bad, err.strip()[:400]))
        done += 1
    print("fuzz_numbers: %d cases in %.0f s (seed %d), exit statuses %s, %d failed" % (
        done, time.time() - t0, o.seed, dict(sorted(statuses.items(), key=str)), failed))
    return 1 if failed or done == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
