#!/usr/bin/env bash
# Runs the CUDA build's tests and the headline measurements on a GPU machine; logs to ${OUT:-gpu-out}.
#   bench/gpu_check.sh [build/cuda] [check|tests|hashes|bench|all]   (after scripts/bundle-libs.sh build/cuda)
# check = tests + hashes.
set -uo pipefail
b=${1:-build/cuda}; what=${2:-all}; out=${OUT:-gpu-out}; mkdir -p "$out"
export LD_LIBRARY_PATH=$PWD/$b/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH} OMP_PROC_BIND=false
w=$b/bin/weft
has() { [ "$what" = all ] || [ "$what" = "$1" ] || { [ "$what" = check ] && [ "$1" != bench ]; }; }
{ nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv; $w info; } 2>&1 | tee "$out/info.log"
if has tests; then {
  echo "== tests"
  # Each test in its own process, so one crash cannot hide the others.
  t=$b/bin/weft_tests_cuda; pass=0; fail=0
  for name in $($t --gtest_list_tests | awk '/^[^ ]/ {s=$1} /^  / {print s $1}'); do
    if $t --gtest_filter="$name" > "$out/test.log" 2>&1; then pass=$((pass + 1)); else
      fail=$((fail + 1)); echo "FAILED $name:"; grep -E "Failure|Expected|Which is|actual|rror|Segmentation" "$out/test.log" | head -6; fi
    grep -E "^(layer-stack|kinetic|ccd|false)" "$out/test.log"
  done
  echo "cuda tests: $pass passed, $fail failed"
} 2>&1 | tee "$out/tests.log"; fi
if has hashes; then {
  echo "== hashes (hanging-sheet, default res, frames 1-24)"
  for cfg in "--backend cuda" "--backend serial" "--backend openmp --threads 1" "--backend openmp --threads 2" "--backend openmp --threads 16"; do
    echo "$cfg: $($w $cfg run builtin:hanging-sheet --frames 1-24 --hash --quiet | tail -1)"
  done
  for scene in drape-sphere layer-stack twist fast-collider skirt; do
    for cfg in "--backend cuda" "--backend openmp --threads 16"; do
      echo "$scene $cfg: $($w $cfg run builtin:$scene --res 12 --frames 1-12 --hash --quiet | tail -1)"
    done
  done
  for scene in layer-stack skirt; do  # the ccd model, with its Jacobi contacts too
    for cfg in "--backend cuda" "--backend openmp --threads 16"; do
      echo "$scene ccd $cfg: $($w $cfg run builtin:$scene --res 12 --frames 1-12 --contact-model ccd --hash --quiet | tail -1)"
      echo "$scene ccd jacobi $cfg: $($w $cfg run builtin:$scene --res 12 --frames 1-12 --contact-model ccd --contact-solver jacobi --hash --quiet | tail -1)"
    done
  done
  if [ -d .devdata/ccd ]; then echo "== ccd-eval"; $w --backend cuda ccd-eval .devdata/ccd | tail -1; fi
} 2>&1 | tee "$out/hashes.log"; fi
if has bench; then {
  # Each measurement under a time limit, so one slow scene cannot eat the whole call.
  lim() { local t=$1; shift; timeout -s INT "$t" "$@" || echo "(stopped or failed after ${t}s: $*)"; }
  echo "== intersections"
  lim 150 $w --backend cuda check-intersections builtin:layer-stack --frame 72 | tail -1 | sed 's/^/layer-stack at frame 72: /'
  lim 200 $w --backend cuda check-intersections builtin:twist --frame 97 | tail -1 | sed 's/^/twist after two turns: /'
  echo "== skirt timing in contact (cuda, about 300K triangles, 16 warm-up frames), proximity contacts, tethers"
  lim 200 $w --backend cuda bench builtin:skirt --res 87 --frames ${SKIRT_FRAMES:-2} --schedules paper --tethers 1 --json "$out/skirt-87-tethers.json"
  echo "== the same, the ccd model (the paper's), no tethers"
  lim 200 $w --backend cuda bench builtin:skirt --res 87 --frames ${SKIRT_FRAMES:-2} --schedules paper --contact-model ccd --json "$out/skirt-87-ccd.json"
  echo "== 50-layer drop in contact (476K triangles)"
  lim 120 $w --backend cuda bench builtin:layer-drop --res 69 --warmup 9 --frames 2 --json "$out/drop-69.json"
  echo "== hanging-sheet timing (cuda)"
  lim 120 $w --backend cuda bench builtin:hanging-sheet --res 388 --frames 5 --schedules paper --json "$out/sheet-388.json"
  if [ -x "$b/bin/weft_bench_cuda" ]; then
    echo "== microbenchmarks (cuda)"
    lim 120 $b/bin/weft_bench_cuda --benchmark_min_time=0.05 --benchmark_out="$out/micro-cuda.json" --benchmark_out_format=json
  fi
} 2>&1 | tee "$out/bench.log"; fi
