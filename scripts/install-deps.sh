#!/usr/bin/env bash
# Installs what granular-dsmc needs to build, test and document itself, from Debian's packages;
# with --clang only the clang toolchain of scripts/clang-fuzz.sh (sanitizers, libFuzzer), which CI
# does not run. Idempotent: packages already present are skipped, so a second run costs one dpkg query.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libgsl-dev            # root finding, quadrature (theory)
  libsundials-dev       # CVODE (partial-temperature ODEs)
  libhdf5-dev hdf5-tools  # H5MD output; h5dump for users and tests
  libeigen3-dev         # small dense linear algebra (theory)
  libgtest-dev googletest # unit tests
  doxygen graphviz      # `cmake --build build --target docs`
  python3-matplotlib python3-h5py python3-numpy  # paper-figures/
  libopenmpi-dev openmpi-bin  # mpirun: replicas and sweep points over ranks
  procps                # pkill, pgrep: tests/scale_out (restart.sh, interrupt.sh) signal the runs they start
)
case "${1:-}" in
  "") ;;
  --clang) packages=(clang libclang-rt-dev) ;;  # only these: scripts/clang-fuzz.sh (sanitizers, libFuzzer; tests/fuzz)
  *) echo "install-deps: unknown option '$1' (none, or --clang)" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
