#!/usr/bin/env bash
# weft batch on a real Slurm (scripts/slurm-local.sh: a controller and one node on localhost): a wedge of three
# tasks is submitted as one job array, one task is requeued mid-run (Slurm stops it with SIGTERM and runs it
# again), and every cache ends complete, the requeued task's with the same hash as a straight run.
#   bash tests/farm_slurm.sh WEFT SOURCE_DIR      exit 0 pass, 1 fail, 77 skip (no Slurm installed)
set -euo pipefail
weft=$1 src=$2
for tool in slurmctld slurmd munged sbatch squeue scontrol; do
  command -v "$tool" >/dev/null || { echo "skip: $tool is not installed (bash scripts/slurm-local.sh install)"; exit 77; }
done
[ "$(id -u)" = 0 ] || { echo "skip: the local Slurm runs as root"; exit 77; }

work=$(mktemp -d /tmp/weft-farm-slurm-XXXXXX)
# Ports of our own, so that a cluster left by another run does not answer for this one.
export SLURM_LOCAL_CTLD_PORT=$((20000 + $$ % 20000)) SLURM_LOCAL_SLURMD_PORT=$((20001 + $$ % 20000))
cleanup() { bash "$src/scripts/slurm-local.sh" stop "$work/cluster" >/dev/null 2>&1 || true; rm -rf "$work"; }
trap cleanup EXIT
eval "$(bash "$src/scripts/slurm-local.sh" start "$work/cluster")"
fail() { echo "FAIL: $*"; "$weft" batch status "$work/wedge.json" || true; cat "$work"/out/*/log.txt || true; exit 1; }

cat > "$work/wedge.json" <<JSON
{"name": "w", "output": "out", "backend": "openmp", "threads": 1,
 "tasks": [{"name": "sheet", "scene": "builtin:hanging-sheet", "res": 24, "frames": "1-60",
            "wedge": {"bend_stiffness_scale": [0.5, 1, 2]}}],
 "slurm": {"cpus_per_task": 1, "time": "00:10:00"}}
JSON
"$weft" batch plan "$work/wedge.json"
out=$("$weft" batch submit "$work/wedge.json" --scheduler slurm) || fail "submit: $out"
echo "$out"
job=$(sed -n 's/^submitted job \([0-9]*\):.*/\1/p' <<<"$out")
[ -n "$job" ] || fail "no job id in: $out"

frames_of() { "$weft" batch status "$work/wedge.json" | awk -v t="$1" '$1 == t { split($3, f, "/"); print f[1] + 0 }'; }
state_of() { "$weft" batch status "$work/wedge.json" | awk -v t="$1" '$1 == t { print $2 }'; }

# Requeue sheet-1 once it is running and has written a few frames: Slurm sends it SIGTERM, weft ends the frame
# in progress, and the task runs again, continuing its cache.
for _ in $(seq 600); do
  [ "$(state_of sheet-1)" = running ] && [ "$(frames_of sheet-1)" -ge 5 ] && break
  sleep 0.1
done
before=$(frames_of sheet-1)
[ "$before" -ge 5 ] && [ "$before" -lt 60 ] || fail "sheet-1 was not caught mid-run ($before frames)"
scontrol requeue "${job}_1"
echo "requeued ${job}_1 at $before frames"
for _ in $(seq 100); do scontrol update JobId="${job}_1" StartTime=now 2>/dev/null && break; sleep 0.1; done

for _ in $(seq 1800); do
  "$weft" batch status "$work/wedge.json" | grep -q '^3 of 3 tasks done' && break
  sleep 0.2
done
"$weft" batch status "$work/wedge.json"
"$weft" batch status "$work/wedge.json" | grep -q '^3 of 3 tasks done' || fail "not every task is done"
grep -q "restart 1" "$work/out/sheet-1/log.txt" || fail "sheet-1 ran only once"
grep -q "stopped by SIGTERM" "$work/out/sheet-1/log.txt" || fail "sheet-1 was not stopped by Slurm's SIGTERM"
grep -q "resuming from" "$work/out/sheet-1/log.txt" || fail "sheet-1 did not continue its cache"

collected=$("$weft" batch collect "$work/wedge.json" --no-sheets)
echo "$collected"
for t in sheet-0 sheet-1 sheet-2; do
  grep -q "^  $t  *done  *frames 60/60 .*intersections 0 " <<<"$collected" || fail "$t is not complete"
done
straight=$("$weft" --backend openmp --threads 1 run builtin:hanging-sheet --res 24 --frames 1-60 \
           --set bend_stiffness_scale=1 --hash --quiet | sed -n 's/^hash //p')
got=$(sed -n 's/^  sheet-1 .* hash \([0-9a-f]*\)$/\1/p' <<<"$collected")
[ "$got" = "$straight" ] || fail "requeued sheet-1 has hash $got, a straight run $straight"
echo "PASS: 3 tasks complete; sheet-1 requeued at frame $before gives the straight run's hash $straight"
