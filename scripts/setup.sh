#!/usr/bin/env bash
# perifem set-up on Debian 12: install what the build and the tests need (only what is
# missing), configure and build, then run the main example (--example) or the tests (--test).
#   bash scripts/setup.sh --example   # install, build, run inputs/panel_impact.yaml on every core
#   bash scripts/setup.sh --test      # install, build (warnings as errors), run ctest
#   bash scripts/setup.sh             # install, build and install perifem (PERIFEM_PREFIX, default
#                                     # /usr/local: the library, its header and pkg-config file, the
#                                     # executable and the Python package)
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(build-essential cmake pkg-config
  libopenmpi-dev openmpi-bin
  libtrilinos-zoltan-dev libmetis-dev
  libexodusii-dev libnetcdf-mpi-dev libhdf5-openmpi-dev
  libgmsh-dev libtrilinos-pamgen-dev libyaml-dev libmuparser-dev petsc-dev calculix-ccx
  python3 python3-venv python3-pip python3-setuptools python3-numpy python3-h5py python3-netcdf4 python3-matplotlib python3-mpi4py python3-yaml netcdf-bin
  valgrind)

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# mpirun refuses to run as root without these (containers, CI).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

mode="${1:-build}"
werror=OFF
[ "$mode" = "--test" ] && werror=ON
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPERIFEM_WERROR=$werror >/dev/null
cmake --build build -j"$(nproc)" 2>&1 | grep -v "^\[" || true
test -x build/perifem || { echo "setup: build failed" >&2; exit 1; }
# Install the executable, libperifem.so.0, perifem.h, perifem.pc and the Python package (import
# perifem with /usr/bin/python3) under PERIFEM_PREFIX (default /usr/local).
prefix=${PERIFEM_PREFIX:-/usr/local}
$SUDO cmake --install build --prefix "$prefix" >/dev/null
case "$prefix" in /usr | /usr/local) $SUDO ldconfig ;; esac

case "$mode" in
  --example)
    mkdir -p run
    cd run && mpirun -np "$(nproc)" ../build/perifem --progress plain ../inputs/panel_impact.yaml
    /usr/bin/python3 ../scripts/panel_sweep.py --report panel_impact.h5
    /usr/bin/python3 ../scripts/plot_history.py panel_impact.h5 --out plots
    echo "open run/panel_impact.e in ParaView (File > Open; colour by 'eqps' or 'damage'); plots in run/plots/"
    ;;
  --test)
    ctest --test-dir build --output-on-failure -LE slow -j"$(nproc)"
    ;;
  build) ;;
  *) echo "usage: bash scripts/setup.sh [--example | --test]" >&2; exit 2 ;;
esac
