#!/usr/bin/env bash
# weft as a library, from outside: installs this build into a scratch prefix, configures and builds
# examples/consumer against it as another project would (find_package(weft)), runs it, and checks that its
# hash is the one `weft run` gives for the same scene and frames on the same backend. Exits 77 (a skip)
# when something it needs is missing.
#   package_consumer.sh BUILD_DIR SOURCE_DIR KOKKOS_ROOT CXX_COMPILER GENERATOR WEFT [COMPILER_LAUNCHER]
set -uo pipefail
build=$1 src=$2 kokkos=$3 cxx=$4 generator=$5 weft=$6 launcher=${7:-}
cmake=${CMAKE_COMMAND:-cmake}
skip() { echo "package_consumer: skipped: $*"; exit 77; }
fail() { echo "package_consumer: FAILED: $*"; exit 1; }
command -v "$cmake" >/dev/null || skip "no cmake"
compgen -G "$kokkos/lib*/cmake/Kokkos/KokkosConfig.cmake" >/dev/null || skip "no Kokkos package under $kokkos"
[ -x "$weft" ] || skip "no weft program at $weft"

# A fixed scratch folder in the build tree: a failed run leaves it to look at, and a compiler launcher
# (ccache) sees the same paths on the next run.
scratch=$build/tests/package_consumer
rm -rf "$scratch"
mkdir -p "$scratch"
run() {  # the command's output goes to a log, shown when it fails
  local log=$scratch/$1.log; shift
  "$@" >"$log" 2>&1 || { cat "$log"; fail "$*"; }
}
run install "$cmake" --install "$build" --prefix "$scratch/prefix"
run configure "$cmake" -S "$src/examples/consumer" -B "$scratch/build" -G "$generator" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER="$cxx" ${launcher:+-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher"} \
  -Dweft_ROOT="$scratch/prefix" -DKokkos_ROOT="$kokkos"
run build "$cmake" --build "$scratch/build"

# One thread each: OpenMP threads that wait at every kernel's barrier for a descheduled sibling make a
# sub-second run take minutes on a busy machine, and the hash is the same at any thread count.
export OMP_NUM_THREADS=1 OMP_PROC_BIND=false
out=$("$scratch/build/weft_consumer") || { rc=$?; echo "$out"; fail "weft_consumer exited with $rc"; }
echo "$out"
got=$(tail -n 1 <<<"$out")
backend=$(sed -n 's/.*, backend \([a-z]*\),.*/\1/p' <<<"$out")
grep -q "weft initialised Kokkos: no" <<<"$out" || fail "weft::Runtime initialised Kokkos over the application's"
want=$("$weft" --backend "$backend" --threads 1 run builtin:hanging-sheet --res 8 --frames 1-4 --hash --quiet | tail -n 1)
echo "weft run --backend $backend: $want"
[[ $got == hash\ * && $got == "$want" ]] || fail "the consumer's '$got' is not weft run's '$want'"
echo "package_consumer: passed"
