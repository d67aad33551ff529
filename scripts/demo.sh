#!/usr/bin/env bash
# Sets everything up, builds the default (openmp) preset and runs the default demo: a sheet draped over a
# sphere, written as an HDF5 cache and a Houdini .geo sequence under demo/.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/build.sh openmp
mkdir -p demo
build/openmp/bin/weft info
exec build/openmp/bin/weft run builtin:drape-sphere --res 16 --frames 1-48 -o demo/drape-sphere.h5 \
  --geo-sequence demo/geo --hash
