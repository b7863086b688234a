"""perifem.campaign on the glass disk struck by a rigid sphere (4 mm disk, 150 steps), after
python/examples/campaign_disk.py wrote example.csv (6 replicas, seed 3, s00 normal with CoV 0.1):
  - the example's replicas: the s00 values of the plan, damage fractions in (0, 1) that fall as s00
    rises (of two replicas whose s00 differ by more than 5 %, the larger breaks fewer bonds; closer
    values may come out either way), a folder and a history.csv each;
  - zero scatter: 3 replicas with one digest and identical outputs, CoV exactly 0;
  - the seed: replicas 0 and 1 of a 2-replica campaign with seed 3 are the example's replicas 0
    and 1 (values, outputs and digests);
  - the spread: with the same seed (the same normal deviates), s00's CoV 0.2 gives a standard
    deviation of the damage fraction more than twice that of CoV 0.02;
  - the lattice perturbation (amplitude 0.05 h): each replica its own seed, digests all different;
  - the workers' allocator asks for huge pages: a worker sees the user's glibc tunables with
    glibc.malloc.hugetlb=1 after them, and the user's environment is as it was after the run;
  - the distributions: 2000 draws of each give back its parameters (the Weibull ones by
    perifem.basis' fit);
  - a replica whose drawn s00 is not positive fails alone (perifem refuses the value), the
    statistics are those of the others; a lambda as an output (the workers cannot import it) is
    refused before any replica starts.
usage: python3 test_campaign.py DECK example.csv   (PYTHONPATH holds the package)"""
import csv
import os
import sys

import numpy as np

from perifem import basis, campaign

deck, example = sys.argv[1], sys.argv[2]
SMALL = {"bodies.disk.geometry.radius": 0.004, "time.final_time": 1.5e-5}
OUTPUTS = {"damage_fraction": campaign.final("damage_fraction"), "peak_force_N": campaign.peak("sphere_force_z")}
S00 = "bodies.disk.damage.s00"
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def worker_tunables(history):
    """1 when this worker's glibc tunables are the test's own followed by the huge-page switch."""
    return float(os.environ.get("GLIBC_TUNABLES") == "glibc.malloc.arena_max=4:glibc.malloc.hugetlb=1")


def run(folder, replicas, scatter, seed, perturbation=None):
    return campaign.run(deck, replicas, scatter=scatter, seed=seed, outputs=OUTPUTS, folder=folder, workers=2,
                        overrides=SMALL, perturbation=perturbation)


if __name__ == "__main__":
    rows = list(csv.DictReader(open(example)))
    s00 = np.array([float(r[S00]) for r in rows])
    damage = np.array([float(r["damage_fraction"]) for r in rows])
    planned = [p[S00] for p in campaign.plan(6, {S00: ("normal", 5e-4, 5e-5)}, seed=3)]
    check(len(rows) == 6 and list(s00) == planned, "the example's 6 replicas carry the planned s00 values")
    pairs = [(i, j) for i in range(6) for j in range(6) if s00[j] > 1.05 * s00[i]]
    check(np.all((damage > 0) & (damage < 1)) and pairs and all(damage[j] < damage[i] for i, j in pairs),
          "damage fractions %s in (0, 1); of two replicas whose s00 differ by more than 5 %%, the larger s00 "
          "breaks fewer bonds (%d pairs)" % (np.round(damage, 4).tolist(), len(pairs)))
    check(all(os.path.isfile("campaign_disk/replica_%04d/history.csv" % i) for i in range(6)),
          "each replica has its folder and its history.csv")

    draws = {name: np.array([p["x"] for p in campaign.plan(2000, {"x": spec}, seed=1)])
             for name, spec in (("normal", ("normal", 5e-4, 5e-5)), ("lognormal", ("lognormal", -7.6, 0.1)),
                                ("weibull", ("weibull", 12.0, 5e-4)), ("uniform", ("uniform", 1.0, 3.0)))}
    shape, scale = basis.weibull_fit(draws["weibull"])
    ln = np.log(draws["lognormal"])
    check(abs(draws["normal"].mean() / 5e-4 - 1) < 0.01 and abs(draws["normal"].std() / 5e-5 - 1) < 0.05
          and abs(ln.mean() / -7.6 - 1) < 0.001 and abs(ln.std() / 0.1 - 1) < 0.05
          and abs(shape / 12 - 1) < 0.05 and abs(scale / 5e-4 - 1) < 0.01
          and 1 <= draws["uniform"].min() and draws["uniform"].max() <= 3 and abs(draws["uniform"].mean() - 2) < 0.05,
          "2000 draws: normal mean %.4g sd %.4g; lognormal ln mean %.4f sd %.4f; Weibull fit shape %.2f scale %.4g; "
          "uniform in [%.3f, %.3f]" % (draws["normal"].mean(), draws["normal"].std(), ln.mean(), ln.std(), shape, scale,
                                       draws["uniform"].min(), draws["uniform"].max()))

    mixed = run("mixed", 3, {S00: ("uniform", -5e-4, 6e-4)}, seed=2)
    negative = [i for i, p in enumerate(campaign.plan(3, {S00: ("uniform", -5e-4, 6e-4)}, seed=2)) if p[S00] <= 0]
    check(negative and [r["index"] for r in mixed.failed] == negative and "must be positive" in mixed.failed[0]["error"]
          and mixed.statistics("damage_fraction")["n"] == 3 - len(negative),
          "a drawn s00 <= 0 (replicas %s) fails its replica only (\"%s\"); the others finish"
          % (negative, mixed.failed[0]["error"][:60] if mixed.failed else ""))

    try:
        campaign.run(deck, 2, outputs={"x": lambda history: 1.0}, folder="lambda")
        refused = ""
    except TypeError as e:
        refused = str(e)
    check("module level" in refused and not os.path.exists("lambda"),
          "a lambda as an output function is refused before any replica starts")

    zero = run("zero", 3, {S00: ("fixed", 5e-4)}, seed=1)
    digests = {r["digest"] for r in zero.replicas}
    d = zero.statistics("damage_fraction")
    check(len(digests) == 1 and len({r["outputs"]["damage_fraction"] for r in zero.replicas}) == 1
          and d["std"] == 0 and d["cov"] == 0,
          "zero scatter: one digest %s, damage CoV %g" % (sorted(digests), d["cov"]))

    again = run("again", 2, {S00: ("normal", 5e-4, 5e-5)}, seed=3)
    same = all(r["digest"] == rows[i]["digest"] and r["overrides"][S00] == s00[i]
               and repr(r["outputs"]["damage_fraction"]) == rows[i]["damage_fraction"]
               for i, r in enumerate(again.replicas))
    check(same, "seed 3, 2 replicas: the example's replicas 0 and 1 again (digests %s)"
          % [r["digest"] for r in again.replicas])

    narrow = run("narrow", 4, {S00: ("normal", 5e-4, 1e-5)}, seed=5).statistics("damage_fraction")
    wide = run("wide", 4, {S00: ("normal", 5e-4, 1e-4)}, seed=5).statistics("damage_fraction")
    check(wide["std"] > 2 * narrow["std"] > 0,
          "damage fraction's std %.4g for s00 CoV 0.2, %.4g for CoV 0.02 (ratio %.1f)"
          % (wide["std"], narrow["std"], wide["std"] / narrow["std"] if narrow["std"] else float("inf")))

    shaken = run("perturbed", 2, {S00: ("fixed", 5e-4)}, seed=1, perturbation={"disk": 0.05})
    seeds = [r["overrides"]["bodies.disk.geometry.seed"] for r in shaken.replicas]
    shaken_digests = {r["digest"] for r in shaken.replicas}
    check(len(set(seeds)) == 2 and len(shaken_digests) == 2 and not shaken_digests & digests,
          "lattice perturbation 0.05 h, seeds %s: digests %s, unlike the unperturbed run's"
          % (seeds, sorted(shaken_digests)))

    before = os.environ.get("GLIBC_TUNABLES")
    os.environ["GLIBC_TUNABLES"] = "glibc.malloc.arena_max=4"
    tuned = campaign.run(deck, 1, outputs={"tunables": worker_tunables}, folder="tunables", workers=1,
                         overrides=SMALL)
    check(list(tuned.values("tunables")) == [1.0] and os.environ["GLIBC_TUNABLES"] == "glibc.malloc.arena_max=4",
          "the worker's glibc tunables: the user's, then glibc.malloc.hugetlb=1; the user's kept")
    if before is None:
        del os.environ["GLIBC_TUNABLES"]
    else:
        os.environ["GLIBC_TUNABLES"] = before
    sys.exit(1 if failures else 0)
