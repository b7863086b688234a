"""A virtual-allowables campaign through the Python package: the glass disk struck by a rigid
sphere (inputs/disk_impact_rigid.yaml; Silling & Askari 2005) run as N replicas, each with its
own critical stretch s00 drawn from a normal distribution (and, with --perturbation, its own
random offset of the lattice points), each in its own process and folder. For each replica it
takes the damage fraction and the energy released at the end and the largest force on the sphere,
then prints their mean, standard deviation, coefficient of variation and B- and A-basis values
(normal and Weibull; CMH-17-1G), and writes one CSV row a replica.

  /usr/bin/python3 python/examples/campaign_disk.py [--replicas 20] [--seed 1]
      [--s00 5e-4] [--s00-cov 0.1] [--perturbation 0] [--radius 0.006] [--final-time 1.5e-5]
      [--workers 2] [--folder campaign_disk] [--out campaign_disk.csv] [--plot damage.png]

The defaults make a small campaign (a 6 mm disk, 150 steps: about a second a replica); the
deck's own disk is --radius 0.037 --final-time 1e-4. No deck file is edited: each replica's
values are overrides."""
import argparse
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, ".."))  # the package beside this folder, if not installed
from perifem import campaign  # noqa: E402

OUTPUTS = {"damage_fraction": campaign.final("damage_fraction"),
           "released_J": campaign.final("damage_dissipation"),
           "peak_force_N": campaign.peak("sphere_force_z")}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--deck", default=os.path.join(here, "..", "..", "inputs", "disk_impact_rigid.yaml"))
    ap.add_argument("--replicas", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--s00", type=float, default=5e-4, help="the mean critical stretch (the deck's: 5e-4)")
    ap.add_argument("--s00-cov", type=float, default=0.1, help="its coefficient of variation (0: no scatter)")
    ap.add_argument("--perturbation", type=float, default=0.0,
                    help="lattice perturbation amplitude, in lattice spacings (0: none)")
    ap.add_argument("--radius", type=float, default=0.006, help="the disk's radius, m")
    ap.add_argument("--final-time", type=float, default=1.5e-5, help="s")
    ap.add_argument("--workers", type=int, default=2, help="replicas run at once")
    ap.add_argument("--folder", default="campaign_disk", help="the replicas' folders go here")
    ap.add_argument("--out", help="write one CSV row a replica")
    ap.add_argument("--plot", help="a histogram of the damage fraction (PNG; needs matplotlib)")
    a = ap.parse_args()
    scatter = {"bodies.disk.damage.s00": ("normal", a.s00, a.s00 * a.s00_cov) if a.s00_cov > 0 else ("fixed", a.s00)}
    result = campaign.run(a.deck, a.replicas, scatter=scatter, seed=a.seed, outputs=OUTPUTS, folder=a.folder,
                          workers=a.workers, perturbation={"disk": a.perturbation} if a.perturbation else None,
                          overrides={"bodies.disk.geometry.radius": a.radius, "time.final_time": a.final_time})
    print(result.report())
    if a.out:
        result.write_csv(a.out)
    if a.plot and not result.plot("damage_fraction", a.plot):
        print("no plot: matplotlib is not installed")


if __name__ == "__main__":
    main()
