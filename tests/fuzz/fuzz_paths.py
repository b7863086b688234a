#!/usr/bin/env python3
"""File-kind fuzzing of the paths a run writes ("Nothing silently wrong"): each case runs the
small PD deck of tests/fuzz/decks (an LPS bar that checkpoints every 2 steps) with one or two of
its written paths - output.file, output.history_file, restart.file, --output-dir - pointing at
something of the wrong kind: a FIFO, a character device (a node with /dev/null's numbers, or a
symbolic link to /dev/null where nodes cannot be made), a folder, the deck itself or a symbolic
link to it, another output's path, the checkpoint's temporary file, a dangling symbolic link, a
path of several hundred characters in folders that do not exist, or a plain file already there.

A case passes when perifem
  - refuses (exit 2, naming a deck key or the path) every path that is not absent, a regular file
    or a link to a place a regular file may be written (FIFO, device, folder, an input, another
    output or its temporary file; for --output-dir, anything but a folder or nothing), and writes
    nothing then (no file appears in the case folder);
  - otherwise exits 0, or exits 1 or 2 with a "perifem error" message;
  - never crashes, hangs (--timeout seconds) or changes the deck, a FIFO, a device or a folder it
    was given.
The cases come from a seeded generator (the same seed, the same cases); the default run stops after
--budget seconds (30) or --cases cases (60), whichever comes first.

  python3 tests/fuzz/fuzz_paths.py PERIFEM SCRATCH [--seed N] [--cases N] [--budget S]
"""
import argparse
import hashlib
import os
import random
import re
import shutil
import stat
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
KEYS = ["output.file", "output.history_file", "restart.file", "--output-dir"]
# kinds of thing a path may name; BAD ones must be refused
KINDS = ["fifo", "device", "folder", "the_deck", "link_to_deck", "other_output", "checkpoint_tmp",
         "dangling_link", "long_missing", "existing_file"]
BAD = {"fifo", "device", "folder", "the_deck", "link_to_deck", "other_output", "checkpoint_tmp"}
# for --output-dir a folder is what it names, and a plain file is of the wrong kind
BAD_DIR = {"fifo", "device", "the_deck", "link_to_deck", "existing_file"}
CRASH = re.compile(r"Segmentation|Abort|core dumped|Bus error|Floating point exception|Illegal instruction|"
                   r"AddressSanitizer|runtime error:|stack smashing|double free|malloc\(\): |buffer overflow")


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def make_device(path):
    try:
        os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    except (PermissionError, OSError):
        os.symlink("/dev/null", path)


def kind_of(path):
    """what is at path now (not following a last symbolic link)"""
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return "absent"
    for test, name in ((stat.S_ISFIFO, "fifo"), (stat.S_ISCHR, "device"), (stat.S_ISDIR, "folder"),
                       (stat.S_ISLNK, "link"), (stat.S_ISREG, "file")):
        if test(st.st_mode):
            return name
    return "other"


def place(kind, key, case_dir, deck, taken):
    """make the thing of this kind for key in case_dir; its path (relative to case_dir where it
    can be) and what must still be there after the run (path, kind) or None"""
    name = {"output.file": "out.e", "output.history_file": "out.h5", "restart.file": "ck.h5",
            "--output-dir": "outdir"}[key]
    path = os.path.join(case_dir, "x_" + name)
    if kind == "fifo":
        os.mkfifo(path)
        return path, (path, "fifo")
    if kind == "device":
        make_device(path)
        return path, (path, kind_of(path))
    if kind == "folder":
        os.mkdir(path)
        return path, (path, "folder")
    if kind == "the_deck":
        return deck, None
    if kind == "link_to_deck":
        os.symlink(deck, path)
        return path, (path, "link")
    if kind == "other_output":
        return taken.get("other", os.path.join(case_dir, "deck.e")), None
    if kind == "checkpoint_tmp":
        return os.path.join(case_dir, "deck.restart.h5.tmp"), None
    if kind == "dangling_link":
        os.symlink(os.path.join(case_dir, "nowhere", name), path)
        return path, None
    if kind == "long_missing":
        return os.path.join(case_dir, *(["d" * 60] * 6), name), None
    with open(path, "w") as f:  # existing_file
        f.write("an old file\n")
    return path, None


def cases(seed):
    rng = random.Random(seed)
    while True:
        n = rng.choice([1, 1, 2])
        keys = rng.sample(KEYS, n)
        yield [(k, rng.choice([k2 for k2 in KINDS if not (k == "--output-dir" and k2 in
                                                           ("other_output", "checkpoint_tmp"))]))
               for k in keys]


def run_case(exe, scratch, number, case, timeout):
    case_dir = os.path.join(scratch, "case%03d" % number)
    os.makedirs(case_dir)
    deck = os.path.join(case_dir, "deck.yaml")
    shutil.copy(os.path.join(HERE, "decks", "pd.yaml"), deck)
    before_deck = digest(deck)
    sets, args, keep, taken = [], [], [], {}
    for key, kind in case:
        if key != "output.file":
            taken["other"] = taken.get("other", os.path.join(case_dir, "deck.e"))
        path, kept = place(kind, key, case_dir, deck, taken)
        if kept:
            keep.append(kept)
        if key == "--output-dir":
            args += ["--output-dir", path]
        else:
            sets += ["--set", "%s=%s" % (key, path)]
    made = set(os.listdir(case_dir))
    t0 = time.time()
    try:
        p = subprocess.run([exe] + args + sets + ["deck.yaml"], cwd=case_dir, capture_output=True, text=True,
                           timeout=timeout, stdin=subprocess.DEVNULL)
        status, out = p.returncode, p.stdout + p.stderr
    except subprocess.TimeoutExpired:
        return "hung (over %g s)" % timeout, time.time() - t0
    problems = []
    if status < 0 or CRASH.search(out):
        problems.append("crashed (status %d)" % status)
    bad = [k for k in case if k[1] in (BAD_DIR if k[0] == "--output-dir" else BAD)]
    if bad and status != 2:
        problems.append("exit %d for %s (expected 2: refused)" % (status, ", ".join("%s -> %s" % k for k in bad)))
    if status == 2:
        if "key '" not in out and "perifem error" not in out:
            problems.append("exit 2 without a message naming the key or path")
        new = set(os.listdir(case_dir)) - made
        if new:
            problems.append("refused but wrote %s" % sorted(new))
    elif status not in (0,) and "perifem error" not in out:
        problems.append("exit %d without a message" % status)
    if digest(deck) != before_deck:
        problems.append("the deck changed")
    for path, kind in keep:
        if kind_of(path) != kind:
            problems.append("%s was a %s, now %s" % (os.path.basename(path), kind, kind_of(path)))
    return "; ".join(problems), time.time() - t0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("perifem")
    ap.add_argument("scratch")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", type=int, default=60)
    ap.add_argument("--budget", type=float, default=30.0)
    ap.add_argument("--timeout", type=float, default=20.0)
    a = ap.parse_args()
    exe = os.path.abspath(a.perifem)
    os.makedirs(a.scratch, exist_ok=True)
    start, failures, n = time.time(), 0, 0
    for n, case in enumerate(cases(a.seed), 1):
        if n > a.cases or time.time() - start > a.budget:
            n -= 1
            break
        problem, took = run_case(exe, os.path.abspath(a.scratch), n, case, a.timeout)
        if problem:
            failures += 1
            print("FAIL case %d (%s): %s" % (n, ", ".join("%s -> %s" % k for k in case), problem))
    print("fuzz_paths: seed %d, %d cases, %d failures, %.0f s" % (a.seed, n, failures, time.time() - start))
    return 1 if failures or n == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
