#!/usr/bin/env bash
# Runs the CUDA build's tests and the headline measurements on a GPU machine; logs to ${OUT:-gpu-out}.
#   bench/gpu_check.sh [build/cuda] [check|bench|all]     (after scripts/bundle-libs.sh build/cuda)
set -uo pipefail
b=${1:-build/cuda}; what=${2:-all}; out=${OUT:-gpu-out}; mkdir -p "$out"
export LD_LIBRARY_PATH=$PWD/$b/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH} OMP_PROC_BIND=false
w=$b/bin/weft
if [ "$what" != bench ]; then {
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv
  $w info
  echo "== tests"
  # Each test in its own process, so one crash cannot hide the others.
  t=$b/bin/weft_tests_cuda; pass=0; fail=0
  for name in $($t --gtest_list_tests | awk '/^[^ ]/ {s=$1} /^  / {print s $1}'); do
    if $t --gtest_filter="$name" > "$out/test.log" 2>&1; then pass=$((pass + 1)); else
      fail=$((fail + 1)); echo "FAILED $name:"; grep -E "Failure|Expected|Which is|actual|rror|Segmentation" "$out/test.log" | head -6; fi
    grep -E "^(layer-stack|kinetic|ccd|false)" "$out/test.log"
  done
  echo "cuda tests: $pass passed, $fail failed"
  echo "== hashes (hanging-sheet, default res, frames 1-24)"
  for cfg in "--backend cuda" "--backend serial" "--backend openmp --threads 1" "--backend openmp --threads 2" "--backend openmp --threads 16"; do
    echo "$cfg: $($w $cfg run builtin:hanging-sheet --frames 1-24 --hash --quiet | tail -1)"
  done
  for scene in drape-sphere layer-stack twist fast-collider skirt; do
    for cfg in "--backend cuda" "--backend openmp --threads 16"; do
      echo "$scene $cfg: $($w $cfg run builtin:$scene --res 12 --frames 1-12 --hash --quiet | tail -1)"
    done
  done
  if [ -d .devdata/ccd ]; then echo "== ccd-eval"; $w --backend cuda ccd-eval .devdata/ccd | tail -1; fi
} 2>&1 | tee "$out/check.log"; fi
if [ "$what" != check ]; then {
  echo "== intersections"
  $w --backend cuda check-intersections builtin:layer-stack --frame 72 | tail -1 | sed 's/^/layer-stack at frame 72: /'
  $w --backend cuda check-intersections builtin:twist --frame 97 | tail -1 | sed 's/^/twist after two turns: /'

  echo "== hanging-sheet timing (cuda)"
  for res in 224 388; do $w --backend cuda bench builtin:hanging-sheet --res $res --frames 10 --schedules paper --json "$out/sheet-$res.json"; done
  echo "== skirt timing (cuda)"
  $w --backend cuda bench builtin:skirt --res 87 --frames 10 --schedules paper --json "$out/skirt-87.json"
} 2>&1 | tee "$out/bench.log"; fi
