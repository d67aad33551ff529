#!/usr/bin/env python3
"""Bitwise agreement of backends and thread counts ("Measure it", item 5).

Runs every built-in scene (`weft run builtin:NAME --res R --frames 1-N --hash --quiet`, whose last line is
`hash <16 hex digits>`, a hash of every frame's positions) on Serial, on OpenMP at 1, 2 and 16 threads, and on
CUDA when the binary has it (`weft info` lists the backends), and writes a Markdown table of the hashes with a
column "all equal". Exits 1 when any hash differs or a run gives none.

    python3 bench/reports/cross_backend.py                       # res 6, frames 1-4: a few minutes on 2 cores
    python3 bench/reports/cross_backend.py --res 24 --frames 24  # on a GPU machine

Writes OUT/cross_backend.md, OUT/cross_backend.json and OUT/log.txt.
"""
import argparse
import json
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import weftlib as W  # noqa: E402


def builtin_scenes(weft):
    """The built-in scene names, from the error weft gives for an unknown one (io/builtin_scenes.cpp)."""
    r = W.run_weft(weft, ["run", "builtin:?", "--quiet"], backend="serial", timeout=60)
    m = re.search(r"known: ([^)]*)\)", "\n".join(r.stderr))
    if not m:
        sys.exit("error: could not list the built-in scenes: " + "\n".join(r.stderr))
    return [s.strip() for s in m[1].split(",")]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    W.add_common_args(ap, W.REPO / "bench" / "reports" / "out" / "cross_backend")
    ap.add_argument("--res", type=int, default=6, help="resolution of every built-in scene (default %(default)s)")
    ap.add_argument("--frames", type=int, default=4, help="frames 1-N are run (default %(default)s)")
    ap.add_argument("--threads", default="1,2,16", help="OpenMP thread counts (default %(default)s)")
    ap.add_argument("--scenes", help="comma-separated built-in scenes (default: every one the binary has)")
    ap.add_argument("--backends", help="comma-separated backends (default: every one the binary has)")
    ap.add_argument("--timeout", type=float, default=120,
                    help="seconds per run before it is killed (default %(default)s); after a run of a scene is killed, "
                    "that scene's other configurations are skipped")
    a = ap.parse_args()
    weft = W.check_weft(a.weft)
    info = W.weft_info(weft)
    backends = a.backends.split(",") if a.backends else info["backends"]
    scenes = a.scenes.split(",") if a.scenes else builtin_scenes(weft)
    configs = []
    for b in ("serial", "openmp", "cuda"):
        if b not in backends:
            continue
        if b == "openmp":
            configs += [(b, int(t)) for t in a.threads.split(",")]
        else:
            configs.append((b, None))
    labels = [b if t is None else f"{b} {t}t" for b, t in configs]
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    log = open(out / "log.txt", "w", buffering=1)
    W.progress(f"weft {info['version']} at {weft}: {len(scenes)} scenes x {len(configs)} configurations "
               f"({', '.join(labels)}), res {a.res}, frames 1-{a.frames}")
    results = []
    for scene in scenes:
        hashes = {}
        for (b, t), label in zip(configs, labels):
            if any(v == "(timeout)" for v in hashes.values()):
                hashes[label] = "(skipped)"
                W.progress(f"{scene:14s} {label:10s} skipped: an earlier configuration timed out")
                continue
            r = W.run_weft(weft, ["run", f"builtin:{scene}", "--res", a.res, "--frames", f"1-{a.frames}", "--hash",
                                  "--quiet"], backend=b, threads=t, timeout=a.timeout, log=log)
            h = W.parse_hash(r) if r.rc == 0 else None
            hashes[label] = h or f"({r.status})"
            W.progress(f"{scene:14s} {label:10s} {hashes[label]}  {r.wall:.1f} s"
                       + (f"  {r.message}" if r.message else ""))
        vals = list(hashes.values())
        equal = all(v == vals[0] for v in vals) and not vals[0].startswith("(")
        results.append({"scene": scene, "hashes": hashes, "all_equal": equal})
    log.close()
    rows = [[r["scene"]] + [f"`{r['hashes'][l]}`" for l in labels] + ["yes" if r["all_equal"] else "**NO**"]
            for r in results]
    md = (f"# Cross-backend hashes\n\nweft {info['version']} (`{weft}`); `weft [--backend B] [--threads N] run "
          f"builtin:NAME --res {a.res} --frames 1-{a.frames} --hash --quiet`. A hash covers every frame's positions; "
          "a run that gives none shows its status in parentheses.\n\n"
          + W.md_table(["scene"] + labels + ["all equal"], rows))
    (out / "cross_backend.md").write_text(md)
    (out / "cross_backend.json").write_text(json.dumps({"weft": weft, "version": info["version"], "res": a.res,
                                                         "frames": a.frames, "configurations": labels,
                                                         "results": results}, indent=1) + "\n")
    print(md)
    bad = [r["scene"] for r in results if not r["all_equal"]]
    missing = [r["scene"] for r in results if any(h.startswith("(") for h in r["hashes"].values())]
    differ = [s for s in bad if s not in missing]
    msg = []
    if differ:
        msg.append(f"hashes DIFFER for {', '.join(differ)}")
    if missing:
        msg.append(f"no hash from some configurations of {', '.join(missing)}")
    W.progress(f"wrote {out / 'cross_backend.md'}: " + ("; ".join(msg) if msg else
                                                        "every scene gives one hash on every configuration"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
