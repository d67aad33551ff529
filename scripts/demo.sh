#!/usr/bin/env bash
# Sets everything up, builds the default (openmp) preset and runs the default demo.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/build.sh openmp
exec build/openmp/bin/weft info
