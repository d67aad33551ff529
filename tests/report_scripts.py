#!/usr/bin/env python3
"""The five report scripts of bench/reports/ and weft's side of bench/peers/newton_compare.py, each run end to
end at a tiny size against the built weft.

    python3 tests/report_scripts.py --weft build/openmp/bin/weft

Checks what each report says, not its timings: the hashes agree (and a differing one makes the exit code 1),
a schedule equal to the reference has error exactly 0 and the same bits on Serial and OpenMP, every case and
sweep point has its figures, and each plot is a PNG. Exits 77 (CTest's skip) when Python lacks numpy, h5py
or matplotlib, which scripts/setup.sh installs.
"""
import argparse
import json
import math
import os
import stat
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
REPORTS = ROOT / "bench" / "reports"
PNG = b"\x89PNG\r\n\x1a\n"


def run(script, *args, expect=0):
    cmd = [sys.executable, str(REPORTS / script), *map(str, args)]
    r = subprocess.run(cmd, capture_output=True, text=True, env={**os.environ, "OMP_PROC_BIND": "false"})
    if r.returncode != expect:
        sys.exit(f"FAIL {' '.join(cmd)}: exit {r.returncode}, expected {expect}\n{r.stdout}\n{r.stderr}")
    return r


def check(ok, what):
    if not ok:
        sys.exit(f"FAIL {what}")


def is_png(path):
    return path.is_file() and path.read_bytes()[:8] == PNG


def cross_backend(weft, tmp):
    out = tmp / "cb"
    run("cross_backend.py", "--weft", weft, "--out", out, "--res", 3, "--frames", 2, "--threads", "1,2",
        "--scenes", "hanging-sheet,layer-stack")
    doc = json.loads((out / "cross_backend.json").read_text())
    check([r["scene"] for r in doc["results"]] == ["hanging-sheet", "layer-stack"], "cross_backend: one row per scene")
    for r in doc["results"]:
        check(set(r["hashes"]) == {"serial", "openmp 1t", "openmp 2t"}, f"cross_backend: configurations {r['hashes']}")
        check(r["all_equal"] and len(set(r["hashes"].values())) == 1, f"cross_backend: {r['scene']} hashes differ")
    # A binary whose 2-thread runs give another hash: the report says so and exits 1.
    fake = tmp / "weft-2-threads-differ"
    fake.write_text(f"#!/bin/sh\ncase \" $* \" in *\" --threads 2 \"*) \"{weft}\" \"$@\" | sed 's/^hash .*/hash 0000000000000000/';;\n"
                    f"*) exec \"{weft}\" \"$@\";; esac\n")
    fake.chmod(fake.stat().st_mode | stat.S_IXUSR)
    out = tmp / "cb-differ"
    run("cross_backend.py", "--weft", fake, "--out", out, "--res", 3, "--frames", 2, "--threads", "1,2",
        "--scenes", "hanging-sheet", expect=1)
    doc = json.loads((out / "cross_backend.json").read_text())
    check(not doc["results"][0]["all_equal"], "cross_backend: a differing hash is reported")


def error_vs_time(weft, tmp):
    out = tmp / "ev"

    # The reference is paper-3's schedule (20 substeps x 10 iterations x 1 pass), so paper-3's error is 0.
    def args(scenes, out):
        return ["--weft", weft, "--out", out, "--scenes", scenes, "--res", "hanging-sheet=4", "--res", "twist=4",
                "--frames", 4, "--families", "paper,paper-chebyshev", "--reference", "20,10,1", "--backends", "serial,openmp"]

    run("error_vs_time.py", *args("hanging-sheet,twist", out))
    doc = json.loads((out / "error_vs_time.json").read_text())
    rows = doc["rows"]
    for scene in ("hanging-sheet", "twist"):
        ref = [r for r in rows if r["scene"] == scene and r["family"] == "reference"]
        check(len(ref) == 1 and ref[0]["status"] == "ok", f"error_vs_time: {scene} has one reference run")
        grid = [r for r in rows if r["scene"] == scene and r["family"] == "paper"]
        check(sorted((r["backend"], r["schedule"]) for r in grid) ==
              sorted((b, s) for b in ("serial", "openmp") for s in ("paper-1", "paper-2", "paper-3")),
              f"error_vs_time: {scene} runs every paper schedule on both backends")
        for r in grid:
            check(r["status"] == "ok" and math.isfinite(r["error_mean"]) and r["error_mean"] >= 0,
                  f"error_vs_time: {scene} {r['backend']} {r['schedule']}: {r['status']} {r['error_mean']}")
            check(r["intersections_last"] == 0, f"error_vs_time: {scene} {r['schedule']} intersections")
            if r["backend"] == "openmp":
                check(r["same_bits"] == "yes", f"error_vs_time: {scene} {r['schedule']} same bits on serial and openmp")
            if r["schedule"] == "paper-3":
                check(r["error_mean"] == 0 and r["error_max"] == 0, f"error_vs_time: {scene} paper-3 is the reference")
            else:
                check(r["error_mean"] > 0, f"error_vs_time: {scene} {r['schedule']} differs from the reference")
        cheb = [r for r in rows if r["scene"] == scene and r["family"] == "paper-chebyshev"]
        check(sorted(r["schedule"] for r in cheb) == sorted(f"paper-{k}-cheb" for k in (1, 2, 3) for _ in (0, 1)),
              f"error_vs_time: {scene} runs every paper schedule with Chebyshev")
        check(all(r["error_mean"] > 0 for r in cheb), f"error_vs_time: {scene} with Chebyshev differs from the reference")
    check(is_png(out / "error_vs_time.png"), "error_vs_time: the plot is a PNG")
    check((out / "error_vs_time.csv").read_text().count("\n") == len(rows) + 1, "error_vs_time: one CSV line per run")
    # A second call with the same settings reuses the reference.
    r = run("error_vs_time.py", *args("hanging-sheet", out))
    check("reusing" in r.stdout + r.stderr, "error_vs_time: the reference is reused")
    # --merge makes one report of two runs over different scenes.
    run("error_vs_time.py", *args("twist", tmp / "ev-twist"))
    merged = tmp / "ev-merged"
    run("error_vs_time.py", "--merge", out / "error_vs_time.json", tmp / "ev-twist" / "error_vs_time.json", "--out", merged)
    doc = json.loads((merged / "error_vs_time.json").read_text())
    check({r["scene"] for r in doc["rows"]} == {"hanging-sheet", "twist"}, "error_vs_time: --merge keeps both scenes")
    check(is_png(merged / "error_vs_time.png"), "error_vs_time: --merge draws the plot")


def stability(weft, tmp):
    out = tmp / "st"
    cases = ["fast-collider", "compliance-0-stretch"]
    run("stability.py", "--weft", weft, "--out", out, "--cases", ",".join(cases), "--res-scale", 0.1)
    doc = json.loads((out / "stability.json").read_text())
    check(sorted(c["case"] for c in doc["cases"]) == sorted(cases), "stability: one entry per case asked for")
    for c in doc["cases"]:
        check(c["status"] == "ok" and c["non_finite_points"] == 0, f"stability: {c['case']} ran to the end")
        check(set(c["intersections_by_frame"]) and c["intersections_max"] == max(c["intersections_by_frame"].values()),
              f"stability: {c['case']} intersections checked")
        check(c["pass"] == (not c["fail_reasons"]), f"stability: {c['case']} pass agrees with its reasons")
    fc = next(c for c in doc["cases"] if c["case"] == "fast-collider")
    check("penetrating_points_max" in fc, "stability: the moving collider's inside points are counted")
    md = (out / "stability.md").read_text()
    check(all(c in md for c in cases), "stability: the table names every case")
    # A run whose strain passes --diverge-strain is stopped as diverged and fails; --strict then exits 1.
    run("stability.py", "--weft", weft, "--out", tmp / "st-strict", "--cases", "fast-collider", "--res-scale", 0.1,
        "--diverge-strain", 1e-9, "--strict", expect=1)
    c = json.loads((tmp / "st-strict" / "stability.json").read_text())["cases"][0]
    check(c["status"] == "diverged" and not c["pass"], f"stability: a diverged run fails: {c['status']}")
    # An unknown case is an error.
    r = run("stability.py", "--weft", weft, "--out", tmp / "st-bad", "--cases", "no-such-case", expect=1)
    check("no-such-case" in r.stderr, "stability: an unknown case is named")


def scaling(weft, tmp):
    out = tmp / "sc"
    run("scaling.py", "--weft", weft, "--out", out, "--sweep", "2,3", "--extra", "none", "--frames", 1, "--warmup", 1)
    doc = json.loads((out / "scaling.json").read_text())
    rows = doc["rows"]
    check([(r["scene"], r["res"], r["status"]) for r in rows] == [("skirt", 2, "ok"), ("skirt", 3, "ok")],
          f"scaling: one run per resolution: {[(r['scene'], r['res'], r['status']) for r in rows]}")
    check(rows[0]["triangles"] < rows[1]["triangles"], "scaling: triangles grow with the resolution")
    for r in rows:
        check(r["ms_per_frame"] > 0 and r["ms_constraints"] >= 0, f"scaling: res {r['res']} has its stage times")
        check(r["ms_per_frame_fenced"] > 0, f"scaling: res {r['res']} has the fenced run's time per frame")
    check(is_png(out / "scaling.png"), "scaling: the plot is a PNG")
    (out / "scaling.png").unlink()
    run("scaling.py", "--replot", out / "scaling.json", "--out", out)
    check(is_png(out / "scaling.png"), "scaling: --replot draws the plot again")


def peer_comparison(weft, tmp):
    # Newton is optional (never installed by setup): --skip-newton runs weft's side, its timing from the cache,
    # its intersection count and the tables.
    out = tmp / "peer"
    cmd = [sys.executable, str(ROOT / "bench" / "peers" / "newton_compare.py"), "--quick", "--skip-newton",
           "--device", "cpu", "--weft", str(weft), "--weft-backend", "openmp", "--threads", "2", "--out", str(out),
           "--work", str(tmp / "peer-work")]
    r = subprocess.run(cmd, capture_output=True, text=True, env={**os.environ, "OMP_PROC_BIND": "false"})
    check(r.returncode == 0, f"newton_compare: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
    rows = json.loads((out / "results.json").read_text())["rows"]
    seen = [(x["scene"], x["settings"]["self_collision"]) for x in rows]
    check(seen == [("hanging-sheet", True), ("hanging-sheet", False), ("twist", True)], f"newton_compare: rows {seen}")
    for x in rows:
        check(x["ms_per_frame"] > 0 and x["frames_timed"] > 0, f"newton_compare: {x['scene']} is timed")
        check(x["intersections"] == 0 and x["max_intersections_any_frame"] == 0,
              f"newton_compare: weft's {x['scene']} ends free of intersections")
    check("| twist |" in (out / "results.md").read_text(), "newton_compare: the Markdown table has the twist")


def stiff_cloth(weft, tmp):
    out = tmp / "stiff"
    run("stiff_cloth.py", "--weft", weft, "--out", out, "--res", 4, "--grid", "1x2,2x4", "--warmup", 1, "--frames", 1,
        "--backend", "serial")
    doc = json.loads((out / "stiff_cloth.json").read_text())
    rows = {(r["material"], r["substeps"], r["iterations"]): r for r in doc["results"]}
    check(set(rows) == {(m, s, i) for m in ("compliance-0", "stiff-x100") for s, i in ((1, 2), (2, 4))},
          "stiff_cloth: one row per material and schedule")
    check(all(r["status"] == "ok" and r["max_strain"] >= r["p99_strain"] >= 0 for r in rows.values()),
          "stiff_cloth: every run finished with its strain")
    # More sweeps a frame hold the infinitely stiff sheet closer to its rest lengths.
    check(rows[("compliance-0", 2, 4)]["p99_strain"] <= rows[("compliance-0", 1, 2)]["p99_strain"],
          "stiff_cloth: more substeps and iterations, less strain")
    check("Target met by" in (out / "stiff_cloth.md").read_text(), "stiff_cloth: the verdict per material")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--weft", required=True, help="the weft binary (with the serial and openmp backends)")
    a = ap.parse_args()
    missing = []
    for m in ("numpy", "h5py", "matplotlib"):
        try:
            __import__(m)
        except ImportError:
            missing.append(m)
    if missing:
        print(f"SKIP: Python lacks {', '.join(missing)} (scripts/setup.sh installs them: pip install numpy h5py matplotlib)")
        return 77
    weft = Path(a.weft).resolve()
    with tempfile.TemporaryDirectory(prefix="weft-reports-") as d:
        for test in (cross_backend, error_vs_time, stability, stiff_cloth, scaling, peer_comparison):
            test(weft, Path(d))
            print(f"ok  {test.__name__}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
