#!/usr/bin/env bash
# Sets everything up, builds the default (openmp) preset and runs the whole test suite.
#   scripts/test.sh [preset]   (openmp by default; cuda on a machine with an NVIDIA GPU)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
preset=${1:-openmp}
bash scripts/build.sh "$preset"
# Slurm and munge for the farm test (a controller and a node on localhost, started by the test itself).
bash scripts/slurm-local.sh install || echo "test: Slurm could not be installed; the farm_slurm test will skip"
# One test at a time: the OpenMP tests use every core themselves.
ctest --preset "$preset"
