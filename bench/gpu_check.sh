#!/usr/bin/env bash
# Runs the CUDA build's tests and the headline measurements on a GPU machine; logs to ${OUT:-gpu-out}.
#   bench/gpu_check.sh [build/cuda]     (after scripts/bundle-libs.sh build/cuda)
set -uo pipefail
b=${1:-build/cuda}; out=${OUT:-gpu-out}; mkdir -p "$out"
export LD_LIBRARY_PATH=$PWD/$b/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH} OMP_PROC_BIND=false
w=$b/bin/weft
{
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv
  $w info
  echo "== tests"
  $b/bin/weft_tests_cuda 2>&1 | tail -3
  $b/bin/weft_tests_serial 2>&1 | tail -3
  $b/bin/weft_tests_openmp --threads=1 2>&1 | tail -3
  $b/bin/weft_tests_openmp --threads=2 2>&1 | tail -3
  echo "== hashes (hanging-sheet, default res, frames 1-24)"
  for cfg in "--backend cuda" "--backend serial" "--backend openmp --threads 1" "--backend openmp --threads 2" "--backend openmp --threads 16"; do
    echo "$cfg: $($w $cfg run builtin:hanging-sheet --frames 1-24 --hash --quiet | tail -1)"
  done
  for scene in drape-sphere layer-stack twist fast-collider skirt; do
    for cfg in "--backend cuda" "--backend openmp --threads 16"; do
      echo "$scene $cfg: $($w $cfg run builtin:$scene --res 12 --frames 1-12 --hash --quiet | tail -1)"
    done
  done
  echo "== intersections"
  $w --backend cuda check-intersections builtin:twist --frame 97 | tail -1 | sed 's/^/twist after two turns: /'
  $w --backend cuda check-intersections builtin:layer-stack --frame 72 | tail -1 | sed 's/^/layer-stack at frame 72: /'
  if [ -d .devdata/ccd ]; then echo "== ccd-eval"; $w --backend cuda ccd-eval .devdata/ccd | tail -3; fi
} 2>&1 | tee "$out/check.log"
{
  echo "== hanging-sheet timing (cuda)"
  for res in 224 388; do $w --backend cuda bench builtin:hanging-sheet --res $res --frames 10 --schedules paper --json "$out/sheet-$res.json"; done
  echo "== skirt timing (cuda)"
  $w --backend cuda bench builtin:skirt --res 87 --frames 10 --schedules paper --json "$out/skirt-87.json"
} 2>&1 | tee "$out/bench.log"
