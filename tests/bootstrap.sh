#!/usr/bin/env bash
# Set-up on a fresh Debian bookworm machine (as root, or with sudo), then:
#   bash tests/bootstrap.sh demo   installs, builds, runs options/simulate.opts (writes simulate.h5)
#   bash tests/bootstrap.sh test   installs, builds, runs the whole test suite with ctest
# Idempotent: installs only missing Debian packages, reuses ./build.
set -euo pipefail
mode=${1:-demo}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

# libopenblas0-pthread: OpenBLAS as the machine's libblas.so.3 and liblapack.so.3 (Debian's alternatives
# pick it over the reference BLAS that petsc-dev pulls in): the dense Floquet route's LAPACK (Hessenberg
# reduction and QR of the 2N x 2N monodromy) runs several times faster. The pthread build, so that a
# 1-rank run may use threads; under MPI (one rank per core) OPENBLAS_NUM_THREADS=1 below keeps each
# rank on one thread (benchmarks/README.md "OpenBLAS: the dense route before and after").
packages=(g++ make cmake pkg-config git petsc-dev slepc-dev libhdf5-openmpi-dev catch2 openmpi-bin
          libopenblas0-pthread python3 python3-h5py python3-numpy python3-matplotlib)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "== installing Debian packages: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

echo "== configure and build (build/)"
# A unity build (CMake compiles the sources of a target in batches of 8, one
# compiler start and one parse of the PETSc headers per batch): the clean build
# takes about half the time. The same compiler and flags, so the same results;
# a name two sources of one batch both define is a compile error (file-local
# helpers shared by several sources belong in a header of src/core).
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON > build.log 2>&1 || { cat build.log; exit 1; }
# The targets this mode runs: nltopo (demo), and the unit tests with it (test). The benchmarks'
# baselines (benchmarks/, no test runs them) build with a plain `cmake --build build`.
targets=(nltopo)
[ "$mode" != test ] || targets+=(unit_tests)
cmake --build build -j"$(nproc)" --target "${targets[@]}" >> build.log 2>&1 || { tail -50 build.log; exit 1; }

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_NUM_THREADS=1 # one BLAS thread per rank under mpiexec (the ranks already fill the cores)
case "$mode" in
  demo) ./build/nltopo -options_file options/simulate.opts ;;
  # -j: the tests that start no ranks run two at a time; a test that does holds 2 processors
  # (PROCESSORS in tests/CMakeLists.txt), so no core is ever given two ranks' work
  test) cd build && ctest --output-on-failure --timeout 900 -j"$(nproc)" ;;
  *) echo "usage: bash tests/bootstrap.sh demo|test" >&2; exit 2 ;;
esac
