#!/usr/bin/env bash
# "Nothing silently wrong", messages that do not name their cause: a SIGTERM that arrives while
# MPI starts (MPI_Init takes a second or more, before the set-up catches signals) ended perifem
# with no message at all. It must print the set-up's message and exit with status 143. The
# signal is sent once the process has forked MPI's helper, which it does inside MPI_Init when
# the singleton is not isolated (OMPI_MCA_ess_singleton_isolated=0, set here).
#
#   bash tests/regression/early_signal.sh PERIFEM SCRATCH_DIR [TESTS_BINARY_DIR (unused)]
set -u
[ $# -ge 2 ] || { echo "usage: bash $0 PERIFEM SCRATCH_DIR" >&2; exit 2; }
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
here=$(cd "$(dirname "$0")/.." && pwd) # the tests/ folder
scratch=$2
rm -rf -- "$scratch" && mkdir -p -- "$scratch" || exit 1
source "$here/common/mpi_env.sh"
$PY - "$exe" "$here/../inputs/wave_in_bar.yaml" "$scratch" <<'PY'
import os, signal, subprocess, sys, time
exe, deck, out = sys.argv[1:4]
env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "PMI_"))}
# (a singleton starts isolated unless told otherwise, in 0.07 s and without a helper:
# docs/parallel.md, "Start-up"; with the helper MPI_Init is slow, as under a user's own settings)
env["OMPI_MCA_ess_singleton_isolated"] = "0"
p = subprocess.Popen([exe, "--output-dir", out, deck], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
def children(pid):
    kids = []
    for t in os.listdir("/proc/%d/task" % pid):
        try: kids += open("/proc/%d/task/%s/children" % (pid, t)).read().split()
        except OSError: pass
    return kids
t0 = time.time()
while p.poll() is None and not children(p.pid) and time.time() - t0 < 30: time.sleep(0.005)
if p.poll() is not None: sys.exit("perifem ended (exit %s) before MPI_Init forked a helper: nothing to test" % p.returncode)
p.send_signal(signal.SIGTERM)
try: so, se = p.communicate(timeout=30)
except subprocess.TimeoutExpired: p.kill(); sys.exit("perifem did not end within 30 s of a SIGTERM while MPI started")
msg = "perifem: SIGTERM (signal 15) during the set-up: stopped (exit status 143)"
if p.returncode != 143 or msg.encode() not in se:
    sys.exit("SIGTERM while MPI started: exit %s, stderr %r; expected 143 and %r" % (p.returncode, se[:300], msg))
PY
