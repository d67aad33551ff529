#!/usr/bin/env bash
# Installs everything weft needs to build, idempotently; prints what it did.
#   scripts/setup.sh [openmp|cuda ...]   (default: openmp)
# Debian packages: the build tools and libraries below.
# Kokkos: $Kokkos_ROOT when set; otherwise Kokkos 3.4.01 from Debian bookworm's trilinos 13.2.0 source
# package, patched for CUDA 13 / Hopper, built once per backend into $WEFT_CACHE (~/.cache/weft).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cache=${WEFT_CACHE:-$HOME/.cache/weft}
backends=("$@"); [ ${#backends[@]} -gt 0 ] || backends=(openmp)

say() { echo "setup: $*"; }
sudo_cmd() { if [ "$(id -u)" = 0 ]; then "$@"; elif command -v sudo >/dev/null; then sudo "$@"; else
  echo "setup: need root to run: $*" >&2; exit 1; fi; }

# ---- Debian packages -------------------------------------------------------------------------------------
pkgs=(build-essential cmake ninja-build pkg-config dpkg-dev libhdf5-dev libcli11-dev
      libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev libpng-dev zlib1g-dev libcairo2-dev ccache)
missing=()
for p in "${pkgs[@]}"; do dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p"); done
apt_updated=0
if [ ${#missing[@]} -gt 0 ]; then
  say "installing Debian packages: ${missing[*]}"
  sudo_cmd apt-get update -q >/dev/null; apt_updated=1
  sudo_cmd env DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${missing[@]}" >/dev/null
else
  say "Debian packages already installed (${#pkgs[@]})"
fi

# ---- Python for the report scripts (bench/reports/, tested by tests/report_scripts.py) ------------------
py_mods="numpy h5py matplotlib"
if python3 -c "import ${py_mods// /, }" 2>/dev/null; then
  say "Python modules for the reports already installed ($py_mods)"
elif python3 -m pip install --quiet $py_mods >/dev/null 2>&1; then
  say "installed Python modules for the reports ($py_mods)"
else
  say "could not install $py_mods with pip: the report-script test will skip"
fi

# ---- OpenUSD for `weft export --format usd` (optional) ------------------------------------------------------
# PyPI's C++ development wheels of OpenUSD's Sdf (pxr-sdf-dev pulls pxr-tf-dev, pxr-vt-dev, ... and pxr-tbb-dev),
# which cmake/WeftUsd.cmake finds in python3's site-packages, and usd-core, OpenUSD's Python, with which
# tests/usd_export.py reads the files back. Failing here only means a weft without USD export.
usd_pkgs="pxr-sdf-dev==26.8 usd-core"
if python3 -c "import importlib.metadata as m; [m.version(p) for p in ('pxr-sdf-dev', 'usd-core')]" 2>/dev/null; then
  say "OpenUSD wheels already installed (pxr-sdf-dev, usd-core)"
elif python3 -m pip install --quiet $usd_pkgs >/dev/null 2>&1; then
  say "installed OpenUSD wheels ($usd_pkgs): weft export --format usd"
else
  say "could not install $usd_pkgs with pip: weft builds without USD export"
fi

# ---- Kokkos ------------------------------------------------------------------------------------------------
if [ -n "${Kokkos_ROOT:-}" ]; then
  say "using the installed Kokkos at Kokkos_ROOT=$Kokkos_ROOT"
  exit 0
fi

kver=3.4.01
tri_tar=trilinos_13.2.0.orig.tar.gz
tri_sha=0ddb47784ba7b8a6b9a07a4822b33be508feb4ccd54301b2a5d10c9e54524b90
src=$cache/src/kokkos-$kver
# Source and installs carry the hash of the patches they were made with; a changed patch rebuilds them.
patch_id=$(cat "$here"/kokkos/*.patch | sha256sum | cut -c1-16)

fetch_kokkos_source() {
  if [ "$(cat "$src/.weft-patch" 2>/dev/null)" = "$patch_id" ]; then say "Kokkos $kver source already at $src"; return; fi
  rm -rf "$src"
  mkdir -p "$cache/src"
  if [ ! -f "$cache/src/$tri_tar" ]; then
    if ! grep -rqsE '^(deb-src|Types:.*deb-src)' /etc/apt/sources.list /etc/apt/sources.list.d/ ||
       ! apt-cache showsrc trilinos 2>/dev/null | grep -q '^Version: 13.2.0'; then
      say "adding a bookworm deb-src line (/etc/apt/sources.list.d/weft-bookworm-src.list)"
      echo "deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian bookworm main" |
        sudo_cmd tee /etc/apt/sources.list.d/weft-bookworm-src.list >/dev/null
      apt_updated=0
    fi
    [ $apt_updated = 1 ] || { sudo_cmd apt-get update -q >/dev/null; apt_updated=1; }
    say "downloading Debian's trilinos 13.2.0 source package (166 MB)"
    (cd "$cache/src" && apt-get source --download-only -q trilinos=13.2.0-4 >/dev/null 2>&1 ||
                        apt-get source --download-only -q trilinos >/dev/null)
  fi
  echo "$tri_sha  $cache/src/$tri_tar" | sha256sum -c --quiet - ||
    { echo "setup: sha256 mismatch for $cache/src/$tri_tar" >&2; exit 1; }
  say "extracting packages/kokkos and applying scripts/kokkos/*.patch"
  rm -rf "$src.tmp" && mkdir -p "$src.tmp"
  tar -xzf "$cache/src/$tri_tar" -C "$src.tmp" --strip-components=3 Trilinos-trilinos-release-13-2-0/packages/kokkos
  for p in "$here"/kokkos/*.patch; do patch -s -d "$src.tmp" -p1 < "$p"; done
  echo "$patch_id" > "$src.tmp/.weft-patch"
  mv "$src.tmp" "$src"
}

build_kokkos() {  # $1 = backend
  local b=$1 prefix=$cache/kokkos-$kver-$1
  if [ "$(cat "$prefix/.weft-complete" 2>/dev/null)" = "$patch_id" ]; then
    say "Kokkos $kver ($b) already installed at $prefix"; return
  fi
  fetch_kokkos_source
  local opts=(-DKokkos_ENABLE_SERIAL=ON -DKokkos_ENABLE_OPENMP=ON -DKokkos_ENABLE_TESTS=OFF
              -DKokkos_ENABLE_EXAMPLES=OFF -DCMAKE_CXX_STANDARD=17 -DCMAKE_BUILD_TYPE=Release)
  case $b in
    openmp) ;;
    cuda) opts+=(-DKokkos_ENABLE_CUDA=ON -DKokkos_ENABLE_CUDA_LAMBDA=ON -DKokkos_ARCH_HOPPER90=ON
                 -DCMAKE_CXX_COMPILER="$src/bin/nvcc_wrapper") ;;
    *) echo "setup: unknown backend '$b' (openmp|cuda)" >&2; exit 1 ;;
  esac
  say "building Kokkos $kver ($b) into $prefix"
  local bdir=$cache/build/kokkos-$kver-$b
  rm -rf "$bdir" "$prefix"
  cmake -S "$src" -B "$bdir" -G Ninja -DCMAKE_INSTALL_PREFIX="$prefix" "${opts[@]}" >"$cache/kokkos-$b-configure.log" 2>&1 ||
    { tail -30 "$cache/kokkos-$b-configure.log" >&2; exit 1; }
  cmake --build "$bdir" --target install >"$cache/kokkos-$b-build.log" 2>&1 ||
    { tail -30 "$cache/kokkos-$b-build.log" >&2; exit 1; }
  cp "$src/bin/nvcc_wrapper" "$prefix/bin/" 2>/dev/null || true
  echo "$patch_id" > "$prefix/.weft-complete"
  rm -rf "$bdir"
  say "Kokkos $kver ($b) installed"
}

for b in "${backends[@]}"; do build_kokkos "$b"; done
