#!/usr/bin/env bash
# Copies the shared libraries weft's binaries need (CUDA runtime, OpenMP, HDF5, libstdc++ ...) into
# <build>/lib, so the build folder runs on a machine that has only the GPU driver:
#   scripts/bundle-libs.sh build/cuda ; LD_LIBRARY_PATH=build/cuda/lib build/cuda/bin/weft info
set -euo pipefail
build=${1:-build/cuda}
mkdir -p "$build/lib"
for bin in "$build"/bin/*; do
  ldd "$bin" | awk '/=> \// {print $3}'
done | sort -u | while read -r lib; do
  case $(basename "$lib") in
    libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*|libcuda.so*) ;;  # the system's / driver's own
    *) cp -L "$lib" "$build/lib/" ;;
  esac
done
echo "bundle-libs: $(ls "$build/lib" | wc -l) libraries in $build/lib"
