#!/usr/bin/env bash
# Sets everything up, builds the weft program of the default (openmp) preset and runs the demo (docs/demo.md): a figure of capsules
# in a sewn three-layer skirt, about 20K triangles, written to demo/demo.h5 with a PNG contact sheet
# demo/contact-sheet.png. Extra arguments go to `weft demo` (e.g. --size 300000).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
# Only the weft program: the test suite (scripts/test.sh) is most of a full build's time.
WEFT_TARGETS=weft bash scripts/build.sh openmp
build/openmp/bin/weft info
exec build/openmp/bin/weft demo --out demo "$@"
