#!/usr/bin/env bash
# Cuts the wheels in .whl/ (warp-lang alone is ~150 MB) into pieces that fit one device call's 64 MiB, in
# .whl-parts/ (ignored: add `/.whl-parts/` to .git/info/exclude). On the device each call carries one piece
# and copies it to /tmp/peer; bench/peers/README.md gives the commands.
#   bench/peers/split_wheels.sh [MiB per piece, default 40]
set -euo pipefail
size=${1:-40}
ls .whl/*.whl > /dev/null
rm -rf .whl-parts && mkdir .whl-parts
tar -cf - -C .whl $(cd .whl && ls *.whl) | split -b "${size}M" -d -a 2 - .whl-parts/wheels.tar.
(cd .whl-parts && sha256sum wheels.tar.* > SHA256SUMS)
ls -l .whl-parts
