"""Campaigns (virtual allowables): N replicas of one deck, each with its own seeded scatter of
deck values (material constants, damage parameters: any key a --set override reaches) and,
optionally, its own seed of the lattice perturbation; each replica runs in its own process and
its own folder; named outputs are taken from each replica's history and summarised with
mean, standard deviation, coefficient of variation and the B- and A-basis values
(perifem.basis; docs/library.md, "Campaigns").

    from perifem import campaign
    result = campaign.run("inputs/disk_impact_rigid.yaml", replicas=20, seed=7,
                          scatter={"bodies.disk.damage.s00": ("normal", 5e-4, 5e-5)},
                          outputs={"damage": campaign.final("damage_fraction"),
                                   "peak_force": campaign.peak("sphere_force_z")},
                          folder="campaign_out", workers=2)
    print(result.report())

No deck file is edited: the scattered values are overrides, as the command line's --set."""
import csv
import math
import multiprocessing
import os
import pickle

import numpy as np

from . import basis

DISTRIBUTIONS = ("normal", "lognormal", "weibull", "uniform", "fixed")


# ---- scatter ----
def _check_distribution(key, spec):
    if not isinstance(spec, (tuple, list)) or not spec or spec[0] not in DISTRIBUTIONS:
        raise ValueError("scatter of %s: (name, parameters...) with name one of %s, not %r"
                         % (key, ", ".join(DISTRIBUTIONS), spec))
    wanted = {"normal": 2, "lognormal": 2, "weibull": 2, "uniform": 2, "fixed": 1}[spec[0]]
    if len(spec) != wanted + 1:
        raise ValueError("scatter of %s: %s takes %d parameters, not %d" % (key, spec[0], wanted, len(spec) - 1))


def draw(spec, rng):
    """One value of a distribution:
    ("normal", mean, sd)          ("lognormal", mu, sigma): exp of normal(mu, sigma)
    ("weibull", shape, scale)     ("uniform", low, high)     ("fixed", value)"""
    name, a = spec[0], [float(v) for v in spec[1:]]
    if name == "normal":
        return float(rng.normal(a[0], a[1]))
    if name == "lognormal":
        return float(rng.lognormal(a[0], a[1]))
    if name == "weibull":
        return float(a[1] * rng.weibull(a[0]))
    if name == "uniform":
        return float(rng.uniform(a[0], a[1]))
    return a[0]


def replica_rng(seed, index):
    """The random stream of replica index of a campaign seeded with seed: the same replica gets
    the same values whatever the number of replicas."""
    return np.random.default_rng([int(seed), int(index)])


def plan(replicas, scatter=None, seed=0, perturbation=None, overrides=None):
    """The overrides of each replica: a list of {key: value} (fixed overrides, then the
    scattered values drawn in the order of the keys, then per body
    bodies.<body>.geometry.perturbation and .seed: the amplitude given and a seed drawn for the
    replica)."""
    scatter = dict(scatter or {})
    for key, spec in scatter.items():
        _check_distribution(key, spec)
    out = []
    for i in range(replicas):
        rng = replica_rng(seed, i)
        values = dict(overrides or {})
        for key in sorted(scatter):
            values[key] = draw(scatter[key], rng)
        for body in sorted(perturbation or {}):
            values["bodies.%s.geometry.perturbation" % body] = float(perturbation[body])
            values["bodies.%s.geometry.seed" % body] = int(rng.integers(1, 2 ** 31 - 1))
        out.append(values)
    return out


# ---- outputs: built-in extractors of a replica's history {column: array over the sampled steps}
class final:
    """The column's value at the end of the run."""

    def __init__(self, column):
        self.column = column

    def __call__(self, history):
        return float(history[self.column][-1])


class peak:
    """The largest |value| of the column over the run."""

    def __init__(self, column):
        self.column = column

    def __call__(self, history):
        return float(np.max(np.abs(history[self.column])))


class maximum(final):
    """The largest value of the column over the run."""

    def __call__(self, history):
        return float(np.max(history[self.column]))


class minimum(final):
    """The smallest value of the column over the run."""

    def __call__(self, history):
        return float(np.min(history[self.column]))


# ---- running ----
def _run_replica(job):
    """Run one replica in this process: {index, folder, overrides, outputs: {name: value},
    digest, steps, error}; a replica that fails (perifem refuses a drawn value, an output
    function raises) has error set to the message, its outputs nan and digest "".
    job = (index, deck, folder, overrides, outputs, every, output)."""
    index, deck, folder, overrides, outputs, every, output = job
    try:
        return _simulate(index, deck, folder, overrides, outputs, every, output)
    except Exception as e:  # the campaign goes on; the replica is reported as failed
        return {"index": index, "folder": folder, "overrides": overrides, "outputs": dict.fromkeys(outputs, math.nan),
                "digest": "", "steps": 0, "error": "%s: %s" % (type(e).__name__, e)}


def _simulate(index, deck, folder, overrides, outputs, every, output):
    import perifem
    os.makedirs(folder, exist_ok=True)
    rows = []
    with perifem.Simulation(deck, overrides=overrides, output=output, output_dir=folder, quiet=True,
                            progress="plain") as sim:
        sim.step(0)
        names = sim.history_names
        rows.append(sim.history_row())
        while not sim.finished:
            sim.step(every)
            rows.append(sim.history_row())
        digest = sim.digest()
        steps = sim.step_count
    table = np.array(rows)
    history = {name: table[:, k] for k, name in enumerate(names)}
    with open(os.path.join(folder, "history.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(names)
        w.writerows([[repr(float(v)) for v in row] for row in table])
    values = {name: float(fn(history)) for name, fn in outputs.items()}
    return {"index": index, "folder": folder, "overrides": overrides, "outputs": values, "digest": digest,
            "steps": steps, "error": None}


def _check_picklable(outputs):
    """The worker processes get the output functions by name: a lambda or a nested function cannot go."""
    for name, fn in outputs.items():
        try:
            pickle.dumps(fn)
        except Exception as e:
            raise TypeError("output %r: %r cannot be sent to the worker processes (%s); define the function at "
                            "module level" % (name, fn, e)) from None


def run(deck, replicas, scatter=None, seed=0, outputs=None, folder="campaign", workers=None, perturbation=None,
        overrides=None, every=1, output=False, threads=1):
    """Run replicas copies of deck and return a Result.

    scatter      {"key.path": (distribution, parameters...)}: see draw(); e.g.
                 {"materials.glass.bulk_modulus": ("normal", 14.9e9, 0.7e9),
                  "bodies.disk.damage.s00": ("weibull", 12, 5.2e-4)}
    seed         the campaign's seed: replica i draws from the stream (seed, i)
    perturbation {body: amplitude a}: the lattice points of each replica offset by a uniform
                 random vector in [-a h, a h]^3 with a seed of its own (the deck's geometry keys
                 perturbation and seed; lattice shapes only)
    overrides    {"key.path": value} applied to every replica (e.g. a smaller run)
    outputs      {name: function(history) -> float}; history maps each history column to a
                 numpy array over the steps sampled (every `every` steps and the last); the
                 built-ins final(column), peak(column), maximum(column), minimum(column); a
                 function must be importable by name (module level) for the worker processes
    folder       each replica runs in folder/replica_0000, ... (history.csv there; the deck's
                 Exodus and history files too with output=True)
    workers      processes at once (default: the CPUs); threads OpenMP threads of each"""
    deck = os.path.abspath(deck)
    outputs = dict(outputs or {})
    _check_picklable(outputs)
    jobs = []
    for i, values in enumerate(plan(replicas, scatter, seed, perturbation, overrides)):
        jobs.append((i, deck, os.path.abspath(os.path.join(folder, "replica_%04d" % i)), values, outputs, every,
                     output))
    workers = max(1, min(workers or os.cpu_count() or 1, replicas))
    saved = {name: os.environ.get(name) for name in ("OMP_NUM_THREADS", "GLIBC_TUNABLES")}
    os.environ["OMP_NUM_THREADS"] = str(threads)  # read by each worker as it starts
    os.environ["GLIBC_TUNABLES"] = _with_huge_pages(saved["GLIBC_TUNABLES"])  # read by its allocator then
    try:
        with multiprocessing.get_context("spawn").Pool(workers) as pool:
            results = pool.map(_run_replica, jobs, chunksize=1)
    finally:
        for name, value in saved.items():
            if value is None:
                del os.environ[name]
            else:
                os.environ[name] = value
    return Result(results, sorted(scatter or {}), sorted(outputs))


def _with_huge_pages(tunables):
    """glibc's tunables with its allocator asking for transparent huge pages (glibc 2.35 and later;
    older ones ignore it), unless the user's already say: each replica's set-up writes its bond
    rows about twice as fast where pages are otherwise faulted in 4 kB at a time (docs/parallel.md,
    "Huge pages")."""
    if tunables and "glibc.malloc.hugetlb" in tunables:
        return tunables
    return (tunables + ":" if tunables else "") + "glibc.malloc.hugetlb=1"


class Result:
    """A campaign's replicas: .replicas (list of dicts: index, folder, overrides, outputs,
    digest, steps, error), .failed, .values(name), .statistics(name), .report(),
    .write_csv(path), .plot(name, path)."""

    def __init__(self, replicas, scattered, outputs):
        self.replicas = sorted(replicas, key=lambda r: r["index"])
        self.scattered = list(scattered)
        self.output_names = list(outputs)

    @property
    def failed(self):
        """The replicas that failed (their "error" says why)."""
        return [r for r in self.replicas if r["error"]]

    def values(self, name, finished=True):
        """The replicas' values of an output, or of a scattered input key, as a numpy array: of
        the finished replicas (finished=False: of all, nan for the failed ones' outputs)."""
        rows = [r for r in self.replicas if not (finished and r["error"])]
        if name in self.output_names:
            return np.array([r["outputs"][name] for r in rows])
        return np.array([float(r["overrides"][name]) for r in rows])

    def statistics(self, name):
        """basis.summary of the finished replicas' values."""
        return basis.summary(self.values(name))

    def report(self):
        lines = ["%d replicas, %d failed" % (len(self.replicas), len(self.failed))]
        lines += ["  replica %d: %s" % (r["index"], r["error"]) for r in self.failed]
        names = self.scattered + self.output_names
        width = max([len("quantity")] + [len(name) for name in names])
        lines += ["%-*s %5s %12s %12s %8s %12s %12s %12s %12s" % (width, "quantity", "n", "mean", "std", "CoV",
                                                                  "B normal", "A normal", "B Weibull", "A Weibull")]
        for name in names:
            s = self.statistics(name)
            lines.append("%-*s %5d %12.5g %12.5g %8.4f %12.5g %12.5g %12.5g %12.5g"
                         % (width, name, s["n"], s["mean"], s["std"], s["cov"], s["normal_B"], s["normal_A"],
                            s["weibull_B"], s["weibull_A"]))
        return "\n".join(lines)

    def write_csv(self, path):
        """One row a replica: index, the scattered inputs, the outputs, the state digest."""
        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["replica"] + self.scattered + self.output_names + ["digest", "error"])
            for r in self.replicas:
                w.writerow([r["index"]] + [repr(float(r["overrides"][k])) for k in self.scattered]
                           + [repr(r["outputs"][k]) for k in self.output_names] + [r["digest"], r["error"] or ""])

    def plot(self, name, path):
        """A histogram of an output with its mean and basis values (matplotlib; returns False
        without it)."""
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            return False
        x, s = self.values(name), self.statistics(name)
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.hist(x, bins=max(5, int(math.sqrt(x.size)) + 1), color="0.8", edgecolor="0.3")
        for key, style, label in (("mean", "k-", "mean"), ("normal_B", "b--", "B-basis (normal)"),
                                  ("normal_A", "b:", "A-basis (normal)"), ("weibull_B", "r--", "B-basis (Weibull)"),
                                  ("weibull_A", "r:", "A-basis (Weibull)")):
            if math.isfinite(s[key]):
                ax.axvline(s[key], color=style[0], linestyle=style[1:], label="%s %.4g" % (label, s[key]))
        ax.set_xlabel(name)
        ax.set_ylabel("replicas")
        ax.set_title("%s: %d replicas, CoV %.3g" % (name, s["n"], s["cov"]))
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(path, dpi=100)
        plt.close(fig)
        return True
