#!/usr/bin/env bash
# Sets up and builds one preset:  scripts/build.sh [openmp|cuda|debug] [extra cmake -D options]
# Honours Kokkos_ROOT (an installed Kokkos), WEFT_CACHE (where our Kokkos builds live), WEFT_JOBS and
# WEFT_TARGETS (build only these targets, e.g. "weft").
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
preset=${1:-openmp}; shift || true
case $preset in openmp|debug) backend=openmp ;; cuda) backend=cuda ;;
  *) echo "build: unknown preset '$preset' (openmp, cuda, debug)" >&2; exit 2 ;; esac
bash scripts/setup.sh "$backend"
kroot=${Kokkos_ROOT:-${WEFT_CACHE:-$HOME/.cache/weft}/kokkos-3.4.01-$backend}
extra=(-DKokkos_ROOT="$kroot")
[ "$backend" = cuda ] && extra+=(-DCMAKE_CXX_COMPILER="$kroot/bin/nvcc_wrapper")
cmake --preset "$preset" "${extra[@]}" "$@" >/dev/null
jobs=${WEFT_JOBS:-$(nproc)}
echo "build: compiling preset $preset with $jobs jobs"
cmake --build --preset "$preset" -j "$jobs" ${WEFT_TARGETS:+--target $WEFT_TARGETS}
