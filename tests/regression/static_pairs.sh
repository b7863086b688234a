#!/usr/bin/env bash
# Contact pairs between PD points and FE surfaces, and between PD points, under the quasi-static
# solver (docs/theory/quasi_static_methods.md §10), each against the series-spring closed form of its
# penalty law (docs/theory/contact.md §1, §2). Every PD bar here is PMB, 2 x 2 points across: its
# four end points are alike by the square's symmetry, so a contact pushes them alike and the bar
# answers as it does to a displacement of its end layer. Each deck holds that bar alone, pushed at
# its end layer by a displacement, whose reaction gives the bar's own stiffness K (its strong
# surface effect included: K is 0.47 E A / L for the whole bar, 0.51 for a half):
#  - tests/data/static_fe_pd_bars.yaml: an FE bar (neo-Hookean, E A / L = 2e8 N/m) pushed by d =
#    1e-5 m against a PD bar held at its far end, through an FE-surface-to-PD-particle pair
#    (`method: surface`, k = 1e8 N/m on each of the n = 4 end points), 4 load steps. The push
#    against F = d / (L / (E A) + 1 / (n k) + 1 / K): 1e-4 (measured 3.1e-6: the materials'
#    geometric nonlinearity); the pair's force on the FE bar and the held end's reaction equal and
#    opposite to the push within 1e-6; the penalty energy against F^2 / (2 n k) within 1e-5; the
#    ledger's energy error within 1e-5 of the work (measured 2.9e-7);
#  - tests/data/static_pd_bars.yaml: two PD bars end to end, the short-range force between the
#    n = 4 facing pairs (C (r_c - r) V^2 each, C = 18 K_s / (pi delta^5)), 4 load steps:
#    F = d / (2 / K + 1 / (n C V^2)), its energy F^2 / (2 n C V^2), the same tolerances (measured
#    5.7e-6);
#  - tests/data/static_pd_crack.yaml: one PD bar cracked through at mid-length (precracks:) in
#    short-range contact with itself: the crack closes by g = 0.1 h without force (the pair radius
#    of two points of one body, 0.9 of their distance at rest), then F = (d - g) / (2 / K_half +
#    1 / (n C V^2)), the same tolerances (measured 1.4e-5);
#  - the same state digest on 1, 2 and 3 ranks for each deck (2 load steps, tolerance 1e-4).
# usage: static_pairs.sh PERIFEM SCRATCH   (from the tests/ folder)
set -u
exe=$1 scratch=$2 fail=0
data=$(cd data && pwd)
source common/mpi_env.sh
source common/measure.sh
decks="static_fe_pd_bars static_pd_bars static_pd_crack"
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
for deck in $decks; do
  out=$("$exe" --quiet "$data/$deck.yaml" 2>&1) || { echo "FAIL: $deck: $out"; fail=1; }
done
res=$("$PY" - static_fe_pd_bars.h5 static_pd_bars.h5 static_pd_crack.h5 <<'PYEOF'
import sys
import h5py
import numpy as np
ok = True
E, A, L, d, T = 200e9, 1e-4, 0.1, 1e-5, 1e-3
Ks, h, delta, n = 133.333333333e9, 0.005, 0.015075, 4  # the PD bars' bulk modulus, spacing, horizon
C = 18 * Ks / (np.pi * delta ** 5)  # the short-range constant (docs/theory/contact.md §1)
kc = C * h ** 3 * h ** 3  # one pair of points of volume h^3: a spring C V^2


def check(label, f, t, vref, Lbar, pull, spring, pair, sign):
    """The push F (the pushing grip's reaction R along its motion) at each load step against
    `pull`, the series closed form given the stiffness K of the bar alone (of length Lbar, its end
    layer moved at vref t); the held end's reaction -R; `pair` the pair's force on its first body,
    sign R (sign 1: the held body; -1: the pushed one; None: a body with itself)."""
    global ok
    K = f["ref_push_reaction_x"][1:] / (vref * t)  # the bar alone: reaction / displacement
    R = f["push_reaction_x"][1:]
    F = R * np.sign(f["push_displacement_x"][-1])
    cf = pull(K)
    use = cf > 0
    err = np.abs(F[use] / cf[use] - 1).max()
    held = np.abs(f["held_reaction_x"][1:][use] / R[use] + 1).max()
    act = np.abs(f[pair][1:][use] / (sign * R[use]) - 1).max() if pair else 0.0
    U = abs(f["contact_energy"][-1] / (F[-1] ** 2 / (2 * spring)) - 1)
    bal = abs(f["energy_error"][-1]) / f["external_work"][-1]
    print("%s: K / (E A / L_bar) = %.4f; F / closed form - 1 = %s; held end %.2g, pair %.2g off F; penalty energy %.2g off; energy error %.3g of the work"
          % (label, K[-1] / (E * A / Lbar), np.array2string(F[use] / cf[use] - 1, precision=3), held, act, U, bal))
    print("MEASURE %s_force_error %.6g" % (label, err))
    print("MEASURE %s_energy_error %.6g" % (label, bal))
    if not err < 1e-4: print("FAIL: %s: the push is off the series springs" % label); ok = False
    if not (held < 1e-6 and act < 1e-6): print("FAIL: %s: the held end or the pair does not balance the push" % label); ok = False
    if not U < 1e-5: print("FAIL: %s: the penalty energy" % label); ok = False
    if not bal < 1e-5: print("FAIL: %s: the energy balance" % label); ok = False
    if np.abs(f["kinetic_energy"][:]).max() != 0: print("FAIL: %s: kinetic energy" % label); ok = False
    return K


f = h5py.File(sys.argv[1], "r")
t = f["time"][1:]
k = 1e8
K = check("fe_pd", f, t, 0.005, L, lambda K: d * t / T / (L / (E * A) + 1 / (n * k) + 1 / K), n * k, "joint_force_x", -1)
print("MEASURE fe_pd_bar_stiffness %.6g" % (K[-1] / (E * A / L)))
f = h5py.File(sys.argv[2], "r")
t = f["time"][1:]
K = check("short_range", f, t, -0.005, L, lambda K: d * t / T / (2 / K + 1 / (n * kc)), n * kc, "joint_force_x", 1)
f = h5py.File(sys.argv[3], "r")
t = f["time"][1:]
push = 2.5 * np.minimum(t, 2e-4) + 0.0125 * np.maximum(t - 2e-4, 0)  # the deck's grip: g, then d more
if not np.abs(-f["push_displacement_x"][1:] / push - 1).max() < 1e-12: print("FAIL: crack: the grip's motion"); ok = False
K = check("crack", f, t, -0.005, L / 2, lambda K: (push - 0.1 * h) / (2 / K + 1 / (n * kc)), n * kc, None, 0)
print("MEASURE crack_half_stiffness %.6g" % (K[-1] / (E * A / (L / 2))))
if not abs(f["push_reaction_x"][1]) < 1e-6 * abs(f["push_reaction_x"][-1]):
    print("FAIL: crack: a force before the crack closed"); ok = False
sys.exit(0 if ok else 1)
PYEOF
) || fail=1
echo "$res" | grep -v '^MEASURE'
echo "$res" | sed -n 's/^MEASURE //p' | while read -r k v; do pf_measure "$k" "$v" 1; done
for deck in $decks; do
  cp "$data/$deck.yaml" .
  static_digests "$exe" "$deck" || fail=1
done
exit $fail
