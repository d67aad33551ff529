"""Shared helpers of the measurement reports (bench/reports/*.py): run the weft binary, watch it, read caches.

Only the Python standard library, numpy and h5py (matplotlib is imported by the scripts that plot).
"""
import json
import os
import queue
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
DEFAULT_WEFT = REPO / "build" / "openmp" / "bin" / "weft"
SCENES = Path(__file__).resolve().parent / "scenes"

# `weft run` prints one line per frame when stdout is not a terminal (apps/cmd_run.cpp, Progress::frame); the
# fields between the max strain and the time (contacts, fail-safe, pin lag) are skipped.
FRAME_LINE = re.compile(r"^frame (\d+)\s+ke (\S+) J\s+rms speed (\S+) m/s\s+max strain (\S+)\s.*?(\S+) ms$")
NON_FINITE = re.compile(r"(\d+) points became non-finite at frame (\d+)")

_T0 = time.monotonic()
# SIGTERM (e.g. from `timeout`) ends a report like Ctrl-C does: through the finally clauses that stop weft.
signal.signal(signal.SIGTERM, lambda signum, frame: sys.exit(128 + signum))


def progress(msg):
    """A progress line on stdout, with the seconds since the script started."""
    print(f"[{time.monotonic() - _T0:7.1f}s] {msg}", flush=True)


def add_common_args(p, out_default):
    p.add_argument("--weft", default=str(DEFAULT_WEFT),
                   help="path to the weft binary (default: build/openmp/bin/weft of this checkout)")
    p.add_argument("--out", default=str(out_default), help=f"output folder (default: {out_default})")


def add_preset_args(p, full_help):
    """--quick (a small CPU run, the default) or --full (`full_help`), into args.preset (None when neither)."""
    g = p.add_mutually_exclusive_group()
    g.add_argument("--quick", dest="preset", action="store_const", const="quick", help="small CPU run (default)")
    g.add_argument("--full", dest="preset", action="store_const", const="full", help=full_help)


def check_weft(path):
    w = Path(path)
    if not w.is_file() or not os.access(w, os.X_OK):
        sys.exit(f"error: no weft binary at {w} (build one: scripts/build.sh, or pass --weft PATH)")
    return str(w.resolve())


def global_args(backend=None, threads=None):
    a = []
    if backend:
        a += ["--backend", backend]
    if threads:
        a += ["--threads", str(threads)]
    return a


def file_id(path):
    """The first 12 hex digits of a file's SHA-256: which binary computed a kept result."""
    import hashlib
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()[:12]


# `weft info` names each schedule of scene/schedules.hpp (apps/cmd_info.cpp).
SCHEDULE_LINE = re.compile(r"^schedule (\S+): substeps (\d+), iterations (\d+), collision passes (\d+)$")


def weft_info(weft):
    """`weft info`: {'version', 'backends': [...], 'schedules': {name: (substeps, iterations, passes)},
    'lines': [...every line]}."""
    r = subprocess.run([weft, "info"], capture_output=True, text=True, check=True)
    info = {"version": "", "backends": [], "schedules": {}, "lines": r.stdout.splitlines()}
    for line in info["lines"]:
        schedule = SCHEDULE_LINE.match(line)
        if line.startswith("weft "):
            info["version"] = line.split(None, 1)[1]
        elif line.startswith("backends:"):
            info["backends"] = line.split(":", 1)[1].split()
        elif schedule:
            info["schedules"][schedule[1]] = tuple(int(v) for v in schedule.groups()[1:])
    return info


def fastest(backends):
    for b in ("cuda", "openmp", "serial"):
        if b in backends:
            return b
    return backends[0]


class RunResult:
    def __init__(self):
        self.rc = None
        self.status = "ok"        # ok | diverged | timeout | non-finite | error
        self.wall = 0.0
        self.frames = []          # per-frame dicts parsed from stdout: frame, ke, rms_speed, max_strain, ms
        self.stdout = []
        self.stderr = []
        self.non_finite_points = 0
        self.non_finite_frame = None
        self.message = ""
        self.killed = None

    @property
    def last_line(self):
        return self.stdout[-1] if self.stdout else ""

    def to_dict(self):
        return {"rc": self.rc, "status": self.status, "wall_s": round(self.wall, 3), "message": self.message,
                "frames_done": len(self.frames), "non_finite_points": self.non_finite_points,
                "non_finite_frame": self.non_finite_frame}


def run_weft(weft, args, backend=None, threads=None, timeout=None, diverge_strain=None, diverge_speed=None,
             log=None):
    """Runs `weft [--backend B] [--threads N] ARGS...`, reading its per-frame lines as they come.

    The run is killed (SIGKILL to its own process group: a frame of an exploding run can take minutes, and
    SIGTERM waits for the frame in progress) when it passes `timeout` seconds or when a frame's max strain
    exceeds `diverge_strain` or its rms speed `diverge_speed` (m/s). A cache written with -o stays readable up
    to the last complete frame."""
    cmd = [weft] + global_args(backend, threads) + [str(a) for a in args]
    res = RunResult()
    if log:
        log.write("$ " + " ".join(cmd) + "\n")
        log.flush()
    t0 = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, bufsize=1,
                            start_new_session=True)
    q = queue.Queue()

    def pump(stream, tag):
        for line in stream:
            q.put((tag, line.rstrip("\n")))
        q.put((tag, None))

    threads_ = [threading.Thread(target=pump, args=(proc.stdout, "out"), daemon=True),
                threading.Thread(target=pump, args=(proc.stderr, "err"), daemon=True)]
    for t in threads_:
        t.start()
    try:
        _watch(proc, q, res, t0, timeout, diverge_strain, diverge_speed, log)
    finally:  # the script is stopped (Ctrl-C, SIGTERM): its weft run stops with it
        if proc.poll() is None:
            _kill(proc)
    proc.wait()
    res.rc = proc.returncode
    res.wall = time.monotonic() - t0
    killed = res.killed
    if log:
        log.write(f"  (exit {res.rc}, {res.wall:.1f} s{', killed: ' + killed if killed else ''})\n")
        log.flush()
    err = "\n".join(res.stderr)
    m = NON_FINITE.search(err)
    if m:
        res.non_finite_points, res.non_finite_frame = int(m[1]), int(m[2])
    if killed:
        res.status = killed
        if killed == "timeout":
            res.message = f"killed after {timeout:g} s"
    elif m or res.rc == 3:
        res.status = "non-finite"
        res.message = err.strip().splitlines()[-1] if err.strip() else "non-finite points"
    elif res.rc != 0:
        res.status = "error"
        res.message = err.strip().splitlines()[-1] if err.strip() else f"exit {res.rc}"
    return res


def _watch(proc, q, res, t0, timeout, diverge_strain, diverge_speed, log):
    """Reads a run's output lines until both streams close, killing it on time-out or divergence."""
    open_streams, killed = 2, None
    while open_streams:
        left = None if timeout is None else timeout - (time.monotonic() - t0)
        if left is not None and left <= 0 and killed is None:
            killed = "timeout"
            _kill(proc)
            left = 5.0
        try:
            tag, line = q.get(timeout=max(0.05, left) if left is not None else None)
        except queue.Empty:
            continue
        if line is None:
            open_streams -= 1
            continue
        if log:
            log.write(("  " if tag == "out" else "! ") + line + "\n")
        if tag == "err":
            res.stderr.append(line)
            continue
        res.stdout.append(line)
        m = FRAME_LINE.match(line)
        if m:
            fr = {"frame": int(m[1]), "ke": float(m[2]), "rms_speed": float(m[3]), "max_strain": float(m[4]),
                  "ms": float(m[5])}
            res.frames.append(fr)
            why = None
            if diverge_strain is not None and not fr["max_strain"] <= diverge_strain:
                why = f"max strain {fr['max_strain']:.3g} > {diverge_strain:g} at frame {fr['frame']}"
            elif diverge_speed is not None and not fr["rms_speed"] <= diverge_speed:
                why = f"rms speed {fr['rms_speed']:.3g} m/s > {diverge_speed:g} m/s at frame {fr['frame']}"
            if why and killed is None:
                killed, res.message = "diverged", why
                _kill(proc)
    res.killed = killed


def _kill(proc):
    try:
        os.killpg(proc.pid, signal.SIGKILL)  # the group of the child we started (start_new_session)
    except ProcessLookupError:
        pass


def parse_hash(res):
    for line in reversed(res.stdout):
        if line.startswith("hash "):
            return line.split()[1]
    return None


def read_cache(path, want_positions=True):
    """A weft cache (docs/formats.md) as numpy arrays: frames [F], positions [F x N x 3] (or None),
    triangles [T x 3], stats (structured [F]), settings (dict). None when there is no readable cache."""
    import h5py
    path = Path(path)
    if not path.exists():
        return None
    try:
        with h5py.File(path, "r", libver="latest", swmr=True) as f:
            n = f["frames"].shape[0]  # authoritative frame count
            c = {"frames": f["frames"][:n], "triangles": f["triangles"][:], "stats": f["stats"][:n],
                 "settings": {k: _plain(v) for k, v in f["settings"].attrs.items()},
                 "backend": _plain(f.attrs["backend"]), "scene": _plain(f.attrs["scene"])}
            c["positions"] = f["positions"][:n] if want_positions else None
            return c
    except (OSError, KeyError):
        return None


def _plain(v):
    import numpy as np
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, np.generic):
        return v.item()
    return v


def write_obj(path, positions, triangles):
    """An OBJ of one frame; repr() of a float reads back exactly, so nothing is rounded."""
    with open(path, "w") as f:
        for p in positions:
            f.write(f"v {float(p[0])!r} {float(p[1])!r} {float(p[2])!r}\n")
        for t in triangles:
            f.write(f"f {int(t[0]) + 1} {int(t[1]) + 1} {int(t[2]) + 1}\n")


def intersections(weft, positions, triangles, obj_path, backend=None, log=None):
    """Cloth triangle pairs that intersect in one frame held in memory: the frame is written as an OBJ and
    counted as a static mesh by `weft check-intersections` (which also reads cache frames, --frame and
    --all-frames). None when weft refuses the mesh."""
    import numpy as np
    if not np.all(np.isfinite(positions)):
        return None
    write_obj(obj_path, positions, triangles)
    r = run_weft(weft, ["check-intersections", obj_path], backend=backend, timeout=600, log=log)
    os.unlink(obj_path)
    m = re.match(r"intersections (\d+)", r.last_line)
    return int(m[1]) if (r.rc == 0 and m) else None


def md_table(headers, rows):
    out = ["| " + " | ".join(headers) + " |", "| " + " | ".join("---" for _ in headers) + " |"]
    for r in rows:
        out.append("| " + " | ".join(str(x) for x in r) + " |")
    return "\n".join(out) + "\n"


def fmt(x, spec=".3g"):
    if x is None:
        return "-"
    if isinstance(x, float) and x != x:
        return "nan"
    return format(x, spec) if isinstance(x, float) else str(x)


def materialize_scene(name, out_dir, res_scale=1.0, frames=None):
    """Copies bench/reports/scenes/NAME.json into out_dir with grid resolutions and a built-in base scene's
    `res` scaled by res_scale (at least 2 quads), and settings.frames replaced when given. Returns the path."""
    src = SCENES / f"{name}.json"
    doc = json.loads(src.read_text())
    if "res" in doc:
        doc["res"] = max(2, round(doc["res"] * res_scale))
    for c in doc.get("cloth", []):
        if c.get("generator") == "grid":
            c["res"] = [max(2, round(r * res_scale)) for r in c.get("res", [16, 16])]
    if frames is not None:
        doc.setdefault("settings", {})["frames"] = list(frames)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    dst = out_dir / f"{name}.json"
    dst.write_text(json.dumps(doc, indent=1) + "\n")
    return dst


def clean_dir(path):
    path = Path(path)
    if path.exists():
        shutil.rmtree(path)
    path.mkdir(parents=True)
    return path
