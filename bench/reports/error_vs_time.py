#!/usr/bin/env python3
"""Error against time per frame for a grid of solver schedules ("Measure it", item 3).

For each scene (built-in skirt, twist, hanging-sheet), a reference run with far more substeps, iterations and
collision passes than any schedule of the grid, then every schedule of the grid on every backend asked for.
Per run: error = RMS point distance to the reference at fixed checkpoint frames / the diagonal of the
reference garment's bounding box at that frame; max strain over the run; cloth triangle pairs that intersect
at the last frame; kinetic energy at the last frame and over the last quarter of frames; milliseconds per
frame: the median of the cache's per-frame wall time (`seconds`, docs/formats.md), first computed frame left out.

    python3 bench/reports/error_vs_time.py --quick            # small, a few minutes on a 2-core CPU
    python3 bench/reports/error_vs_time.py --full --backends cuda   # built-in resolutions: ~5 min on one H200
    python3 bench/reports/error_vs_time.py --merge A/error_vs_time.json B/error_vs_time.json --out C
                                                                    # one report from runs over different scenes

Writes OUT/error_vs_time.csv, OUT/error_vs_time.png (log-log error against ms/frame, one curve per schedule
family and backend), OUT/error_vs_time.md (the tables and the reference's settings), OUT/error_vs_time.json
(what --merge reads), OUT/log.txt (every weft command and its output) and OUT/reference/<scene>.h5 (reused by
later runs with the same settings).
"""
import argparse
import csv
import json
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import weftlib as W  # noqa: E402

DEFAULT_RES = {"skirt": 24, "twist": 48, "hanging-sheet": 32}  # io/builtin_scenes.cpp

PRESETS = {
    # 2-core CPU: small meshes, one second of animation, a reference 5x beyond the costliest schedule.
    "quick": {"res_scale": 0.25, "frames": 24, "reference": (40, 25, 2), "timeout": 90, "ref_timeout": 120,
              "families": {"substeps": [1, 2, 5, 10, 20], "iterations": [10, 20, 50, 100, 200],
                           "tethers": [10, 20, 50, 100, 200], "small-steps": [5, 20],
                           "chebyshev": [10, 20, 50, 100, 200], "chebyshev-90": [10, 20, 50, 100, 200],
                           "coarse": [10, 20, 50, 100, 200]}},
    # GPU: the built-in resolutions, one second of animation, a reference 20x beyond the costliest schedule in
    # iterations per frame and 2x in substeps (about 5 minutes on one H200).
    "full": {"res_scale": 1.0, "frames": 24, "reference": (100, 40, 4), "timeout": 300, "ref_timeout": 600,
             "families": {"substeps": [1, 2, 5, 10, 20], "iterations": [10, 20, 50, 100, 200],
                          "tethers": [10, 20, 50, 100, 200], "small-steps": [5, 10, 20, 50],
                          "chebyshev": [10, 20, 50, 100, 200], "chebyshev-90": [10, 20, 50, 100, 200],
                          "coarse": [10, 20, 50, 100, 200]}},
}
COARSE_LEVELS = 4  # the coarse families' levels (docs/solver.md, Coarse levels)

FAMILY_TITLES = {
    "substeps": "substeps x (10 it, 1 pass)",
    "iterations": "1 substep, N it, N/10 passes",
    "tethers": "1 substep, N it, N/10 passes, tethers 1",
    "small-steps": "substeps x (1 it, 1 pass)",
    "paper": "paper-1/2/3",
    "chebyshev": "1 substep, N it, N/10 passes, Chebyshev 0.95",
    "paper-chebyshev": "paper-1/2/3, Chebyshev 0.95",
    "chebyshev-90": "1 substep, N it, N/10 passes, Chebyshev 0.9",
    "paper-chebyshev-90": "paper-1/2/3, Chebyshev 0.9",
    "coarse": f"1 substep, N it, N/10 passes, Chebyshev 0.95, {COARSE_LEVELS} coarse levels",
    "paper-coarse": f"paper-1/2/3, Chebyshev 0.95, {COARSE_LEVELS} coarse levels",
}
PAPER_FAMILIES = ("paper", "paper-chebyshev", "paper-chebyshev-90", "paper-coarse")
CHEBYSHEV_RHO = {"chebyshev-90": 0.9, "paper-chebyshev-90": 0.9}  # else 0.95, the default


def schedules(families, chosen, named):
    """(family, label, substeps, iterations, passes, weft arguments) for every schedule of the grid. The
    `tethers` family is `iterations` with `--tethers 1` (docs/solver.md, Tethers); the `paper` family is every
    schedule in `named`, {name: (substeps, iterations, passes)} as `weft info` gives them (scene/schedules.hpp);
    `chebyshev` and `paper-chebyshev` are `iterations` and `paper` with Chebyshev acceleration at 0.95 (the
    default; the `-90` families at 0.9), `coarse` and `paper-coarse` the same with COARSE_LEVELS coarse
    levels; every other family runs plain Gauss-Seidel (`--set chebyshev_rho=0`), as does the reference."""
    out = []
    for fam in chosen:
        for v in (named if fam in PAPER_FAMILIES else families.get(fam, [])):
            if fam == "substeps":
                s, it, cp = v, 10, 1
            elif fam in ("iterations", "tethers", "chebyshev", "chebyshev-90", "coarse"):
                s, it, cp = 1, v, max(1, v // 10)
            elif fam == "small-steps":
                s, it, cp = v, 1, 1
            else:
                s, it, cp = named[v]
            if fam in PAPER_FAMILIES:
                args, label = ["--schedule", v], v
            else:
                args, label = ["--substeps", s, "--iterations", it, "--collision-passes", cp], f"{s}x{it}it{cp}p"
            if fam == "tethers":
                args, label = args + ["--tethers", 1], label + "-t1"
            cheb = fam.endswith(("chebyshev", "chebyshev-90", "coarse"))
            if cheb:  # accelerations measured at equal time (docs/solver.md)
                rho = CHEBYSHEV_RHO.get(fam, 0.95)
                args, label = args + ["--set", f"chebyshev_rho={rho}"], label + ("-cheb" if rho == 0.95 else f"-cheb{rho}")
            if fam.endswith("coarse"):
                args, label = args + ["--set", f"coarse_levels={COARSE_LEVELS}"], label + "-coarse"
            elif not cheb:
                args = args + ["--set", "chebyshev_rho=0"]
            out.append((fam, label, s, it, cp, args))
    return out


def rms_error(x, xr):
    d = np.sqrt(np.mean(np.sum((x - xr) ** 2, axis=1)))
    diag = float(np.linalg.norm(xr.max(axis=0) - xr.min(axis=0)))
    return float(d / diag)


def summarize_cache(cache, first_frame, checkpoints):
    st = cache["stats"]
    frames = [int(f) for f in cache["frames"]]
    computed = [i for i, f in enumerate(frames) if f > first_frame]
    secs = [float(st["seconds"][i]) for i in computed]
    timed = secs[1:] if len(secs) > 1 else secs  # the first computed frame pays for first-touch and caches
    ke = [float(st["kinetic_energy"][i]) for i in computed]
    tail = ke[-max(1, len(ke) // 4):] if ke else []
    return {
        "frames_done": len(computed),
        "last_frame": frames[-1] if frames else None,
        # The median: a frame stalled by another process on a shared machine does not move it.
        "ms_per_frame": 1e3 * float(np.median(timed)) if timed else float("nan"),
        "ms_per_frame_mean": 1e3 * float(np.mean(timed)) if timed else float("nan"),
        "max_strain": float(np.max(st["max_strain"][: len(frames)])) if frames else float("nan"),
        "ke_last": ke[-1] if ke else float("nan"),
        "ke_tail_mean": float(np.mean(tail)) if tail else float("nan"),
        "positions": {c: cache["positions"][frames.index(c)] for c in checkpoints if c in frames},
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    W.add_common_args(ap, W.REPO / "bench" / "reports" / "out" / "error_vs_time")
    W.add_preset_args(ap, "built-in resolutions, for a GPU")
    ap.add_argument("--backends", help="comma-separated, from serial,openmp,cuda (default: every backend of the binary; with --full, "
                    "all but serial)")
    ap.add_argument("--threads", type=int, help="host threads of the openmp backend (weft --threads)")
    ap.add_argument("--scenes", default="skirt,twist,hanging-sheet", help="built-in scenes (default: %(default)s)")
    ap.add_argument("--res-scale", type=float, help="resolution = built-in default x this (quick 0.25, full 1)")
    ap.add_argument("--res", action="append", default=[], metavar="SCENE=N", help="a scene's resolution, overriding --res-scale")
    ap.add_argument("--frames", type=int, help="frames simulated after the initial one (quick 24, full 24)")
    ap.add_argument("--checkpoints", help="frames compared with the reference (default: 4 evenly spaced, the last included)")
    ap.add_argument("--families", default="substeps,iterations,tethers,small-steps,paper,paper-chebyshev", help="schedule families (default: %(default)s)")
    ap.add_argument("--reference", help="reference schedule SUBSTEPS,ITERATIONS,PASSES (quick 40,25,2; full 100,40,4)")
    ap.add_argument("--timeout", type=float, help="seconds per run before it is killed (quick 90, full 300)")
    ap.add_argument("--ref-timeout", type=float, help="seconds for a reference run (quick 120, full 600); a scene "
                    "whose reference fails is skipped")
    ap.add_argument("--diverge-strain", type=float, default=5.0,
                    help="kill a run whose max strain passes this (default %(default)s); it is reported as diverged")
    ap.add_argument("--contact-solver", choices=["gauss-seidel", "jacobi"],
                    help="weft --contact-solver for the grid's runs (the reference keeps the scene's, Gauss-Seidel)")
    ap.add_argument("--keep-caches", action="store_true", help="keep every run's cache under OUT/caches")
    ap.add_argument("--merge", nargs="+", metavar="JSON", help="only merge the error_vs_time.json of earlier runs "
                    "(other scenes, same frames and reference) into one report in OUT")
    a = ap.parse_args()
    if a.merge:
        return merge(a.merge, Path(a.out))
    preset = PRESETS[a.preset or "quick"]
    weft = W.check_weft(a.weft)
    info = W.weft_info(weft)
    weft_id = W.file_id(weft)  # a reference is reused only with the very binary that computed it
    backends = a.backends.split(",") if a.backends else info["backends"]
    if not a.backends and a.preset == "full" and len(backends) > 1:
        backends = [b for b in backends if b != "serial"]  # serial at full resolution: hours per scene
    for b in backends:
        if b not in info["backends"]:
            sys.exit(f"error: {weft} has no {b} backend (it has: {' '.join(info['backends'])})")
    res_scale = a.res_scale if a.res_scale is not None else preset["res_scale"]
    nframes = a.frames or preset["frames"]
    timeout = a.timeout or preset["timeout"]
    ref_timeout = a.ref_timeout or preset["ref_timeout"]
    ref_s, ref_it, ref_cp = (tuple(int(v) for v in a.reference.split(",")) if a.reference else preset["reference"])
    res_over = dict((k, int(v)) for k, v in (r.split("=") for r in a.res))
    first, last = 1, 1 + nframes
    if a.checkpoints:
        checkpoints = sorted(int(c) for c in a.checkpoints.split(","))
    else:
        checkpoints = sorted({first + max(1, round(nframes * q)) for q in (0.25, 0.5, 0.75, 1.0)})
    if set(PAPER_FAMILIES) & set(a.families.split(",")) and not info["schedules"]:
        sys.exit(f"error: `{weft} info` names no schedules (a weft older than scene/schedules.hpp?)")
    grid = schedules(preset["families"], a.families.split(","), info["schedules"])
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "reference").mkdir(exist_ok=True)
    cache_dir = out / "caches"
    cache_dir.mkdir(exist_ok=True)
    log = open(out / "log.txt", "w", buffering=1)
    ref_backend = W.fastest(backends)
    max_cost = max(s * it for _, _, s, it, _, _ in grid)
    max_passes = max(s * cp for _, _, s, _, cp, _ in grid)
    W.progress(f"weft {info['version']} at {weft}; backends {','.join(backends)}; frames {first}-{last}; "
               f"checkpoints {checkpoints}; {len(grid)} schedules x {len(backends)} backends per scene")
    W.progress(f"reference: {ref_s} substeps x {ref_it} iterations, {ref_cp} collision passes per substep "
               f"({ref_s * ref_it} iterations and {ref_s * ref_cp} passes per frame; the grid's most: {max_cost} and "
               f"{max_passes}), on {ref_backend}")

    rows, skipped = [], []
    for scene in a.scenes.split(","):
        res = res_over.get(scene, max(2, round(DEFAULT_RES.get(scene, 32) * res_scale)))
        spec = ["run", f"builtin:{scene}", "--res", res, "--frames", f"{first}-{last}"]
        # The reference: reused when a previous run of this script left a complete one with the same settings.
        ref_path = out / "reference" / f"{scene}-res{res}-f{last}-{ref_s}x{ref_it}x{ref_cp}-weft{weft_id}.h5"
        ref = W.read_cache(ref_path)
        if ref is None or len(ref["frames"]) != last - first + 1:
            W.progress(f"{scene} res {res}: reference run on {ref_backend} ...")
            if ref_path.exists():
                ref_path.unlink()
            r = W.run_weft(weft, spec + ["--substeps", ref_s, "--iterations", ref_it, "--collision-passes", ref_cp,
                                         "--set", "chebyshev_rho=0", "-o", ref_path], backend=ref_backend, threads=a.threads, timeout=ref_timeout,
                           diverge_strain=a.diverge_strain, log=log)
            ref = W.read_cache(ref_path)
            if r.status != "ok" or ref is None:
                done = len(ref["frames"]) - 1 if ref is not None else 0
                why = f"the reference run failed: {r.status}" + (f" ({r.message})" if r.message else "") + \
                    f" after {done} of {last - first} frames"
                W.progress(f"{scene} res {res}: {why}; scene skipped")
                skipped.append((scene, res, why))
                if ref_path.exists():
                    ref_path.unlink()
                continue
        else:
            W.progress(f"{scene} res {res}: reusing {ref_path}")
        rs = summarize_cache(ref, first, checkpoints)
        tris = ref["triangles"]
        npts = ref["positions"].shape[1]
        ref_x = rs["positions"]
        ref_inter = W.intersections(weft, ref_x[checkpoints[-1]], tris, out / "frame.obj", backend=ref_backend, log=log)
        W.progress(f"{scene}: {npts} points, {len(tris)} triangles; reference {rs['ms_per_frame']:.1f} ms/frame, "
                   f"max strain {rs['max_strain']:.3g}, intersections {ref_inter}")
        warn = reference_warning({"intersections_last": ref_inter, "max_strain": rs["max_strain"]})
        if warn:
            W.progress(f"{scene}: WARNING: {warn}")
        rows.append({"scene": scene, "res": res, "points": npts, "triangles": len(tris), "backend": ref_backend,
                     "family": "reference", "schedule": f"{ref_s}x{ref_it}it{ref_cp}p", "substeps": ref_s,
                     "iterations": ref_it, "collision_passes": ref_cp, "iterations_per_frame": ref_s * ref_it,
                     "status": "ok", "frames_done": rs["frames_done"], "ms_per_frame": rs["ms_per_frame"],
                     "ms_per_frame_mean": rs["ms_per_frame_mean"], "error_mean": 0.0, "error_max": 0.0,
                     "error_last": 0.0, "max_strain": rs["max_strain"],
                     "intersections_last": ref_inter, "ke_last": rs["ke_last"], "ke_tail_mean": rs["ke_tail_mean"],
                     "same_bits": "", "message": ""})
        first_bits = {}  # (substeps, iterations, passes, options) -> positions at checkpoints on the first backend
        for b in backends:
            done = {}  # (substeps, iterations, passes, options) -> row: a schedule in two families runs once
            for fam, label, s, it, cp, args in grid:
                key = (s, it, cp, tuple(str(x) for x in args if str(x).startswith(("--tethers", "chebyshev", "coarse"))))
                if key in done:
                    row = dict(done[key], family=fam, schedule=label)
                    rows.append(row)
                    W.progress(f"{scene} {b:6s} {fam:11s} {label:12s} same schedule as {done[key]['schedule']} "
                               f"({done[key]['family']}): not run again")
                    continue
                path = cache_dir / f"{scene}-{b}-{label}.h5"
                if path.exists():
                    path.unlink()
                solver = ["--contact-solver", a.contact_solver] if a.contact_solver else []
                r = W.run_weft(weft, spec + args + solver + ["-o", path], backend=b, threads=a.threads if b == "openmp" else None,
                               timeout=timeout, diverge_strain=a.diverge_strain, log=log)
                c = W.read_cache(path)
                row = {"scene": scene, "res": res, "points": npts, "triangles": len(tris), "backend": b, "family": fam,
                       "schedule": label, "substeps": s, "iterations": it, "collision_passes": cp,
                       "iterations_per_frame": s * it, "status": r.status, "message": r.message}
                sm = summarize_cache(c, first, checkpoints) if c is not None else None
                errs = {}
                if sm:
                    for cpt in checkpoints:
                        if cpt in sm["positions"]:
                            errs[cpt] = rms_error(sm["positions"][cpt], ref_x[cpt])
                    row.update({k: sm[k] for k in ("frames_done", "ms_per_frame", "ms_per_frame_mean", "max_strain",
                                                   "ke_last", "ke_tail_mean")})
                complete = sm is not None and len(errs) == len(checkpoints)
                for cpt in checkpoints:
                    row[f"err_f{cpt}"] = errs.get(cpt, float("nan"))
                row["error_mean"] = float(np.mean(list(errs.values()))) if complete else float("nan")
                row["error_max"] = float(np.max(list(errs.values()))) if complete else float("nan")
                row["error_last"] = errs.get(checkpoints[-1], float("nan"))
                # Bits: every backend must give the first backend's positions exactly.
                common = [k for k in first_bits.get(key, ({},))[0] if sm and k in sm["positions"]]
                if common:  # the checkpoints both runs reached
                    same = all(np.array_equal(sm["positions"][k], first_bits[key][0][k]) for k in common)
                    row["same_bits"] = "yes" if same else "NO"
                    if same and complete and len(first_bits[key][0]) == len(checkpoints):
                        row["intersections_last"] = first_bits[key][1]
                else:
                    row["same_bits"] = "" if b == backends[0] else "-"
                if row.get("intersections_last") is None and complete:
                    row["intersections_last"] = W.intersections(weft, sm["positions"][checkpoints[-1]], tris,
                                                                out / "frame.obj", backend=b, log=log)
                if sm and b == backends[0]:
                    first_bits[key] = (sm["positions"], row.get("intersections_last"))
                done[key] = row
                if not a.keep_caches and path.exists():
                    path.unlink()
                rows.append(row)
                W.progress(f"{scene} {b:6s} {fam:11s} {label:12s} {r.status:8s} "
                           f"{W.fmt(row.get('ms_per_frame'), '.1f'):>8s} ms/frame  error {W.fmt(row['error_mean'])}  "
                           f"max strain {W.fmt(row.get('max_strain'))}  intersections {W.fmt(row.get('intersections_last'))}"
                           + (f"  ({r.message})" if r.message else ""))
    log.close()
    if not rows:
        sys.exit("no results: " + "; ".join(f"{s}: {w}" for s, _, w in skipped))
    meta = {"info": info, "weft": weft, "backends": backends, "threads": a.threads, "first": first, "last": last,
            "checkpoints": checkpoints, "reference": [ref_s, ref_it, ref_cp], "ref_backend": ref_backend,
            "contact_solver": a.contact_solver or "gauss-seidel",
            "timeout": timeout, "diverge_strain": a.diverge_strain, "skipped": skipped}
    write_outputs(out, meta, rows)


def write_outputs(out, meta, rows):
    """error_vs_time.{csv,md,png}, and .json (meta and rows, for --merge)."""
    checkpoints = meta["checkpoints"]
    cols = ["scene", "res", "points", "triangles", "backend", "family", "schedule", "substeps", "iterations",
            "collision_passes", "iterations_per_frame", "status", "frames_done", "ms_per_frame", "ms_per_frame_mean", "error_mean",
            "error_max", "error_last"] + [f"err_f{c}" for c in checkpoints] + [
            "max_strain", "intersections_last", "ke_last", "ke_tail_mean", "same_bits", "message"]
    with open(out / "error_vs_time.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in cols})
    (out / "error_vs_time.json").write_text(json.dumps({"meta": meta, "rows": rows}, indent=1, default=float))
    write_markdown(out / "error_vs_time.md", rows, meta)
    plot(out / "error_vs_time.png", rows, meta["first"], meta["last"])
    differ = [r for r in rows if r.get("same_bits") == "NO"]
    W.progress(f"wrote {out / 'error_vs_time.csv'}, {out / 'error_vs_time.md'}, {out / 'error_vs_time.png'}")
    if differ:
        W.progress(f"WARNING: {len(differ)} runs differ bitwise between backends")


def merge(paths, out):
    """One report from the error_vs_time.json of runs over different scenes (same frames and reference)."""
    parts = [json.loads(Path(p).read_text()) for p in paths]
    meta = parts[0]["meta"]
    for p, part in zip(paths, parts):
        m = part["meta"]
        if (m["first"], m["last"], m["checkpoints"], m["reference"]) != (meta["first"], meta["last"], meta["checkpoints"], meta["reference"]):
            sys.exit(f"error: {p} has other frames, checkpoints or reference than {paths[0]}")
    meta = dict(meta, backends=list(dict.fromkeys(b for part in parts for b in part["meta"]["backends"])),
                skipped=[s for part in parts for s in part["meta"]["skipped"]])
    out.mkdir(parents=True, exist_ok=True)
    write_outputs(out, meta, [r for part in parts for r in part["rows"]])


def write_markdown(path, rows, meta):
    info, weft, backends, threads = meta["info"], meta["weft"], meta["backends"], meta["threads"]
    first, last, checkpoints, ref_backend = meta["first"], meta["last"], meta["checkpoints"], meta["ref_backend"]
    timeout, diverge, skipped = meta["timeout"], meta["diverge_strain"], meta["skipped"]
    s, it, cp = meta["reference"]
    md = ["# Error against time per frame\n\n",
          f"weft {info['version']} (`{weft}`), backends {', '.join(backends)}"
          + (f", openmp threads {threads}" if threads else "") + f". Frames {first}-{last} (the first is the initial state); "
          f"errors at frames {', '.join(map(str, checkpoints))}.\n\n",
          f"**Reference**: {s} substeps per frame x {it} iterations per substep, {cp} collision passes per substep "
          f"({s * it} iterations and {s * cp} collision passes per frame), computed on {ref_backend} with Gauss-Seidel "
          f"contacts; the grid's runs project contacts with {meta.get('contact_solver', 'gauss-seidel')}.\n\n",
          "**error** = RMS over points of |x - x_ref| at a checkpoint frame / diagonal of the reference garment's "
          "bounding box at that frame; `error_mean` is the mean over the checkpoints. **ms/frame**: median wall time "
          "per frame from the cache (`/stats/seconds`), first computed frame left out (the CSV has the mean too). **max strain**: max over "
          "frames of `max_strain` (the triangles' largest principal stretch - 1, docs/solver.md). **intersections**: cloth "
          f"triangle pairs that intersect at frame {checkpoints[-1]} (`weft check-intersections frame.obj`). "
          "**KE**: kinetic energy (J) at the last frame and its mean over the last quarter of frames.\n\n",
          f"Runs are killed after {timeout:g} s (`timeout`) or once max strain passes {diverge:g} (`diverged`); "
          "`same bits` compares the positions at the checkpoints with the first backend's run, bit for bit.\n"]
    for scene in dict.fromkeys(r["scene"] for r in rows):
        rs = [r for r in rows if r["scene"] == scene]
        md.append(f"\n## {scene} (res {rs[0]['res']}: {rs[0]['points']} points, {rs[0]['triangles']} triangles)\n\n")
        warn = reference_warning(rs[0])
        if warn:
            md.append(f"**Warning**: {warn}\n\n")
        md.append(W.md_table(
            ["backend", "family", "schedule", "it/frame", "status", "ms/frame", "error mean", "error max", "max strain",
             "intersections", "KE last", "KE tail", "same bits"],
            [[r["backend"], r["family"], r["schedule"], r["iterations_per_frame"], r["status"],
              W.fmt(r.get("ms_per_frame"), ".2f"), W.fmt(r.get("error_mean")), W.fmt(r.get("error_max")),
              W.fmt(r.get("max_strain")), W.fmt(r.get("intersections_last")), W.fmt(r.get("ke_last")),
              W.fmt(r.get("ke_tail_mean")), r.get("same_bits", "")] for r in rs]))
    for scene, res, why in skipped:
        md.append(f"\n## {scene} (res {res}): skipped\n\n{why}.\n")
    path.write_text("".join(md))


def reference_warning(ref):
    """Why a reference run is not a trustworthy stand-in for the converged motion ('' when nothing is seen)."""
    if not ref.get("intersections_last"):
        return ""
    return (f"the reference run itself has {ref['intersections_last']} intersecting triangle pairs at the last "
            f"checkpoint (max strain {ref['max_strain']:.3g}): errors here are distances to it, not to a converged "
            "solution")


def plot(path, rows, first, last):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    backends = list(dict.fromkeys(r["backend"] for r in rows if r["family"] != "reference"))
    fams = [f for f in FAMILY_TITLES if any(r["family"] == f for r in rows)]
    colours = dict(zip(fams, plt.rcParams["axes.prop_cycle"].by_key()["color"]))
    styles = dict(zip(backends, ["-", "--", ":", "-."]))
    markers = dict(zip(backends, ["o", "s", "^", "D"]))
    fig, axes = plt.subplots(1, len(scenes), figsize=(5.2 * len(scenes), 4.6), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        for b in backends:
            for fam in fams:
                pts = [(r["ms_per_frame"], r["error_mean"]) for r in rows
                       if r["scene"] == scene and r["backend"] == b and r["family"] == fam
                       and _pos(r.get("ms_per_frame")) and _pos(r.get("error_mean"))]
                if pts:
                    xs, ys = zip(*pts)
                    ax.plot(xs, ys, linestyle=styles[b], marker=markers[b], color=colours[fam], markersize=4,
                            label=f"{FAMILY_TITLES[fam]} [{b}]")
        ref = [r for r in rows if r["scene"] == scene and r["family"] == "reference"]
        if ref and _pos(ref[0].get("ms_per_frame")):
            ax.axvline(ref[0]["ms_per_frame"], color="grey", linewidth=0.8, linestyle=":")
            ax.text(ref[0]["ms_per_frame"], 1.0, " reference", color="grey", fontsize=7, rotation=90,
                    va="top", ha="right", transform=ax.get_xaxis_transform())
        failed = [r for r in rows if r["scene"] == scene and r["family"] != "reference" and not _pos(r.get("error_mean"))]
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("ms per frame")
        ax.set_ylabel("RMS error / bbox diagonal")
        ax.set_title(f"{scene} (res {ref[0]['res'] if ref else '?'}, {ref[0]['triangles'] if ref else '?'} tris)"
                     + (f"\n{len(failed)} runs failed (not shown)" if failed else "")
                     + (f"\nthe reference has {ref[0]['intersections_last']} intersections"
                        if ref and reference_warning(ref[0]) else ""), fontsize=9)
        ax.grid(True, which="both", linewidth=0.3)
    h, l = axes[0][0].get_legend_handles_labels()
    for ax in axes[0][1:]:
        for hh, ll in zip(*ax.get_legend_handles_labels()):
            if ll not in l:
                h.append(hh)
                l.append(ll)
    axes[0][-1].legend(h, l, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7, frameon=False)
    fig.suptitle(f"weft: error against time per frame, frames {first}-{last}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def _pos(x):
    return isinstance(x, (int, float)) and x == x and x > 0 and math.isfinite(x)


if __name__ == "__main__":
    main()
