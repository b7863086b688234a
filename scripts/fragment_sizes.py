"""The size distribution of the fragments a run wrote with `output.fragments: true`.

  /usr/bin/python3 scripts/fragment_sizes.py RUN.fragments.csv [--time T] [--body NAME] [--png FILE]

Takes the output time closest to T (default: the last), the fragments of body NAME (default:
every body), and prints, for sizes in points of 1, 2, 3-4, 5-8, ... (doubling), how many
fragments fall in each class and the share of the mass they hold; then the largest ten. With
--png it plots the mass share against the size class (a bar per class, log-scaled size) and the
cumulative share of the mass in fragments of at most n points. A fragment is a connected set of
points joined by intact bonds (docs/user_guide.md, output.fragments)."""
import argparse
import csv
import sys


def read(path, time, body):
    """[(points, mass)] of the fragments at the output time closest to `time` (None: the last)."""
    rows = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            rows.append((float(r["time"]), r["body"], int(r["points"]), float(r["mass"])))
    if not rows:
        sys.exit(f"{path}: no fragments")
    times = sorted({t for t, _, _, _ in rows})
    at = times[-1] if time is None else min(times, key=lambda t: abs(t - time))
    picked = [(n, m) for t, b, n, m in rows if t == at and (body is None or b == body)]
    if not picked:
        sys.exit(f"{path}: no fragment of body '{body}' at t = {at:.6g} s")
    return at, picked


def classes(frags):
    """[(lo, hi, count, mass)] for the size classes [1, 1], [2, 2], [3, 4], [5, 8], ..."""
    largest = max(n for n, _ in frags)
    out, lo, hi = [], 1, 1
    while lo <= largest:
        inside = [m for n, m in frags if lo <= n <= hi]
        out.append((lo, hi, len(inside), sum(inside)))
        lo, hi = hi + 1, 2 * hi
    return out


def plot(table, total, at, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    labels = [f"{lo}" if lo == hi else f"{lo}–{hi}" for lo, hi, _, _ in table]
    share = [m / total for _, _, _, m in table]
    cumulative = [sum(share[: k + 1]) for k in range(len(share))]
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.bar(range(len(table)), share, color="tab:blue", label="mass share of the class")
    ax.plot(range(len(table)), cumulative, "o-", color="tab:red", label="mass in fragments of at most n points")
    ax.set_xticks(range(len(table)), labels, rotation=45)
    ax.set_xlabel("fragment size n (points)")
    ax.set_ylabel("share of the mass")
    ax.set_ylim(0, 1.02)
    ax.set_title(f"fragments at t = {at * 1e3:.3f} ms")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--time", type=float, default=None)
    ap.add_argument("--body", default=None)
    ap.add_argument("--png", default=None)
    a = ap.parse_args()
    at, frags = read(a.csv, a.time, a.body)
    total = sum(m for _, m in frags)
    table = classes(frags)
    print(f"t = {at:.6g} s: {len(frags)} fragments, {sum(n for n, _ in frags)} points, mass {total:.6g} kg")
    print(f"{'size (points)':>14} {'fragments':>10} {'mass share':>11}")
    for lo, hi, count, mass in table:
        print(f"{(str(lo) if lo == hi else f'{lo}-{hi}'):>14} {count:>10} {mass / total:>11.4f}")
    print("largest ten:", sorted((n for n, _ in frags), reverse=True)[:10])
    if a.png:
        plot(table, total, at, a.png)
        print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
