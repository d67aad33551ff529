#!/usr/bin/env python3
"""Time per frame against triangle count ("Measure it", item 2: the sweep and the scaling scenes).

Runs `weft bench builtin:NAME --res R --json ...` for a sweep of the five-layer `skirt` from about 10K to 2M
triangles, then for the scaling scenes: `layer-drop` (50 layers, about 475K triangles at res 69) and `twist`.
Each run times the scene's own schedule (`--schedules current`, or `--schedules paper` for the paper's three)
over a few frames after a warm-up, with the stage times `weft bench` fences (constraints, one collision pass,
contact projection, impact-zone smoothing, crossing fail-safe) and the device memory the run took.

    python3 bench/reports/scaling.py --quick                              # small, a minute on a 2-core CPU
    python3 bench/reports/scaling.py --weft build/cuda/bin/weft --backend cuda   # 10K to 2M, on a GPU machine

Writes OUT/scaling.json, OUT/scaling.csv, OUT/scaling.md (the table) and OUT/scaling.png (log-log ms per frame
and per stage against triangles), and OUT/log.txt (every weft command and its output). Without matplotlib
(a GPU machine) the plot is left out; `--replot OUT/scaling.json` draws it elsewhere.
"""
import argparse
import csv
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import weftlib as W  # noqa: E402

# skirt: 5 layers x 2 x rings x 4 rings triangles = 40 res^2 (io/builtin_scenes.cpp); layer-drop 50 x 2 res^2.
PRESETS = {
    "quick": {"sweep": [4, 6, 8, 12], "extra": [("layer-drop", 3), ("twist", 12)], "frames": 2, "warmup": 1,
              "timeout": 300},
    "full": {"sweep": [16, 27, 50, 87, 158, 224], "extra": [("layer-drop", 69), ("twist", 48)], "frames": 3,
             "warmup": 2, "timeout": 600},
}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    W.add_common_args(ap, W.REPO / "bench" / "reports" / "out" / "scaling")
    W.add_preset_args(ap, "10K to 2M triangles, for a GPU")
    ap.add_argument("--backend", help="serial, openmp or cuda (default: the fastest the binary has)")
    ap.add_argument("--sweep", help="comma-separated skirt resolutions (quick 4,6,8,12; full 16,27,50,87,158,224)")
    ap.add_argument("--extra", help="comma-separated SCENE=RES scaling scenes (full: layer-drop=69,twist=48; 'none')")
    ap.add_argument("--schedules", default="current", choices=["current", "paper"],
                    help="the scene's schedule, or the paper's three (default: %(default)s)")
    ap.add_argument("--contact-solver", choices=["gauss-seidel", "jacobi"], help="weft --contact-solver for every run")
    ap.add_argument("--frames", type=int, help="frames timed per run (quick 2, full 3)")
    ap.add_argument("--warmup", type=int, help="frames run before timing (quick 1, full 2)")
    ap.add_argument("--timeout", type=float, help="seconds per run before it is killed (quick 300, full 600)")
    ap.add_argument("--replot", metavar="JSON", help="only redraw OUT/scaling.png (and .md) from a scaling.json, "
                    "for results from a machine without matplotlib")
    a = ap.parse_args()
    if a.replot:
        doc = json.loads(Path(a.replot).read_text())
        out = Path(a.out)
        out.mkdir(parents=True, exist_ok=True)
        write_markdown(out / "scaling.md", doc["rows"], doc["meta"])
        plot(out / "scaling.png", [r for r in doc["rows"] if r["status"] == "ok"], doc["meta"]["backend"])
        W.progress(f"wrote {out / 'scaling.md'}, {out / 'scaling.png'}")
        return 0
    preset = PRESETS[a.preset or ("full" if a.backend == "cuda" else "quick")]
    weft = W.check_weft(a.weft)
    info = W.weft_info(weft)
    backend = a.backend or W.fastest(info["backends"])
    sweep = [int(r) for r in a.sweep.split(",")] if a.sweep else preset["sweep"]
    extra = preset["extra"]
    if a.extra:
        extra = [] if a.extra == "none" else [(s.split("=")[0], int(s.split("=")[1])) for s in a.extra.split(",")]
    frames, warmup = a.frames or preset["frames"], a.warmup if a.warmup is not None else preset["warmup"]
    timeout = a.timeout or preset["timeout"]
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    runs = [("skirt", r, "sweep") for r in sweep] + [(s, r, "scaling scene") for s, r in extra]

    rows = []
    with open(out / "log.txt", "w") as log:
        for scene, res, kind in runs:
            js = out / f"{scene}-res{res}.json"
            W.progress(f"{scene} --res {res} ({backend})")
            r = W.run_weft(weft, ["bench", f"builtin:{scene}", "--res", res, "--frames", frames, "--warmup", warmup,
                                  "--schedules", a.schedules, "--json", js]
                           + (["--contact-solver", a.contact_solver] if a.contact_solver else []),
                           backend=backend, timeout=timeout, log=log)
            for line in r.stdout + r.stderr:
                log.write("  " + line + "\n")
            if r.rc != 0 or not js.exists():
                rows.append({"scene": scene, "res": res, "kind": kind, "status": r.status, "message": r.message})
                W.progress(f"  {r.status}: {r.message}")
                continue
            doc = json.loads(js.read_text())
            for s in doc["results"]:
                row = {"scene": scene, "res": res, "kind": kind, "status": "ok", "triangles": doc["triangles"],
                       "backend": doc["backend"], **s}
                row["memory_mib"] = s["memory_bytes"] / 2**20 if s["memory_bytes"] >= 0 else None
                row["ms_per_100k_triangles"] = s["ms_per_frame"] * 1e5 / doc["triangles"]
                rows.append(row)
                W.progress(f"  {doc['triangles']} triangles, {s['schedule']}: {s['ms_per_frame']:.1f} ms/frame")

    meta = {"weft": weft, "weft_id": W.file_id(weft), "version": info["version"], "devices": info["lines"],
            "backend": backend, "frames": frames, "warmup": warmup, "schedules": a.schedules}
    tmp = out / "scaling.json.tmp"
    tmp.write_text(json.dumps({"meta": meta, "rows": rows}, indent=1) + "\n")
    tmp.replace(out / "scaling.json")
    cols = ["scene", "res", "kind", "triangles", "schedule", "iterations", "collision_passes", "substeps", "ms_per_frame",
            "ms_per_frame_fenced", "ms_constraints", "ms_per_collision_pass", "ms_lbvh_build", "ms_broad_phase_per_pass", "ms_narrow_phase_per_pass",
            "ms_colouring_per_pass", "ms_contacts", "ms_smoothing", "ms_failsafe", "failsafe_rounds",
            "contacts", "memory_mib", "ms_per_100k_triangles", "status"]
    with open(out / "scaling.csv.tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    (out / "scaling.csv.tmp").replace(out / "scaling.csv")
    write_markdown(out / "scaling.md", rows, meta)
    ok = [r for r in rows if r["status"] == "ok"]
    plotted = False
    try:
        if ok:
            plot(out / "scaling.png", ok, backend)
            plotted = True
    except ImportError:
        W.progress("no matplotlib here: redraw the plot elsewhere with --replot OUT/scaling.json")
    W.progress(f"wrote {out / 'scaling.md'}, scaling.csv, scaling.json" + (", scaling.png" if plotted else ""))
    return 0 if len(ok) == len(rows) else 1


def write_markdown(path, rows, meta):
    head = ["scene", "triangles", "schedule", "ms/frame", "constraints", "one collision pass (broad / narrow / colouring)",
            "tree builds", "contacts (ms)", "smoothing", "fail-safe", "contacts", "memory MiB", "ms per 100K triangles"]
    body = []
    for r in rows:
        if r["status"] != "ok":
            body.append([f"{r['scene']} --res {r['res']}", "-", "-", r["status"], r.get("message", "")] + ["-"] * 8)
            continue
        body.append([f"{r['scene']} --res {r['res']}", f"{r['triangles']:,}", r["schedule"], W.fmt(r["ms_per_frame"], ".1f"),
                     W.fmt(r["ms_constraints"], ".1f"), pass_parts(r), W.fmt(r.get("ms_lbvh_build"), ".1f"),
                     W.fmt(r["ms_contacts"], ".1f"), W.fmt(r["ms_smoothing"], ".1f"), W.fmt(r["ms_failsafe"], ".1f"),
                     W.fmt(r["contacts"], ".0f"), W.fmt(r["memory_mib"], ".0f") if r["memory_mib"] is not None else "-",
                     W.fmt(r["ms_per_100k_triangles"], ".1f")])
    text = (f"# Time per frame against triangle count\n\n`weft bench` on backend {meta['backend']}, "
            f"{meta['frames']} frames timed after {meta['warmup']} warm-up, schedules: {meta['schedules']}; "
            f"weft {meta['version']} (binary {meta['weft_id']}). Stage columns are ms per frame except the "
            f"collision pass (ms each, split into refit and tree queries, narrow phase with CCD, and contact "
            f"colouring); tree builds (one per substep) are outside the passes.\n\n" + W.md_table(head, body))
    tmp = Path(str(path) + ".tmp")
    tmp.write_text(text)
    tmp.replace(path)


def pass_parts(r):
    """One collision pass and, from binaries that time them, its broad phase / narrow phase / colouring."""
    s = W.fmt(r["ms_per_collision_pass"], ".2f")
    if "ms_broad_phase_per_pass" in r:
        s += " (" + " / ".join(W.fmt(r[k], ".2f") for k in ("ms_broad_phase_per_pass", "ms_narrow_phase_per_pass",
                                                             "ms_colouring_per_pass")) + ")"
    return s


def plot(path, rows, backend):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 5))
    sweep = sorted((r for r in rows if r["kind"] == "sweep"), key=lambda r: r["triangles"])
    for sched in sorted({r["schedule"] for r in sweep}):
        pts = [r for r in sweep if r["schedule"] == sched]
        t = [r["triangles"] for r in pts]
        ax.plot(t, [r["ms_per_frame"] for r in pts], "o-", label=f"skirt, ms/frame ({sched})")
        for key, label in (("ms_constraints", "constraints"), ("ms_failsafe", "fail-safe")):
            ax.plot(t, [max(r[key], 1e-3) for r in pts], ".--", label=f"skirt, {label} ({sched})")
        # passes_per_frame counts the early passes too (proximity contacts)
        ax.plot(t, [max(r["ms_per_collision_pass"] * r.get("passes_per_frame", r["collision_passes"] * r["substeps"]), 1e-3)
                    for r in pts], ".:",
                label=f"skirt, collision passes ({sched})")
    for r in rows:
        if r["kind"] != "sweep":
            ax.plot([r["triangles"]], [r["ms_per_frame"]], "s", label=f"{r['scene']} ({r['schedule']})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("cloth triangles")
    ax.set_ylabel("ms per frame")
    ax.set_title(f"weft bench, backend {backend}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    tmp = Path(str(path) + ".tmp.png")
    fig.savefig(tmp, dpi=120)
    plt.close(fig)
    tmp.replace(path)


if __name__ == "__main__":
    sys.exit(main())
