#!/usr/bin/env python3
"""weft next to a peer: Newton's VBD cloth solver with self-contact, on the same scenes, GPU and run.

Runs weft's built-in `hanging-sheet` (at several sizes) and `twist` scenes in Newton (PyPI `newton` and
`warp-lang`, optional: weft never needs them) and in weft (`weft run -o CACHE` for time, `weft
check-intersections CACHE --all-frames` for the count), then writes results.json and results.md: scene, triangles, solver,
ms/frame, the triangle strain (max and 99th percentile) and the intersections of the final frame, settings. Newton's final mesh is written as OBJ and counted by
`weft check-intersections mesh.obj`, so both sides are judged by the same discrete triangle-triangle test
(adjacent triangles judged by their shared vertices).

How weft's scenes (io/builtin_scenes.cpp, constraints/vellum_cloth.hpp, scene/scene.hpp) map to Newton:
  geometry   the same grid: (res+1)^2 points, 2 res^2 triangles with the same alternating diagonals, Y up.
             hanging-sheet: 1 m x 1 m at y = 1; twist: 1 m x 1 m at y = 1.
  pins       hanging-sheet: points 0 and res (two corners of one edge), fixed (Newton: particle not ACTIVE).
             twist: the columns x = -0.5 and x = +0.5, turning in opposite directions about the x axis
             through (y=1, z=0), two turns over frames 1..97 while each edge moves 0.2 m inwards (over
             frames 1..49), then held. As in weft, the per-frame targets are interpolated linearly within a
             frame and set every substep (Newton: written into both states before each substep).
  time       24 fps, 10 substeps per frame, frames 1..72 (hanging-sheet: 71 steps) and 1..121 (twist: 120
             steps), gravity (0, -9.81, 0), no air drag, no velocity damping.
  mass       area density 0.1 kg/m^2 (weft's ClothMaterial default; Newton: add_cloth_mesh density).
  timing     ms per frame = mean over the frames after the first (the first, warm-up, frame includes
             Newton's kernel compilation and CUDA-graph capture; weft: the per-frame times `weft run -o`
             prints), so both time the same frames 2..end. Newton: device synchronized before and after each frame; one CUDA graph per
             frame (as Newton's own examples do) when the device is CUDA and the substeps are even.
  contact    self-contact distance: weft keeps cloth surfaces apart by the sum of the two thicknesses
             (hanging-sheet: 2 x min(5 mm, 0.3 x the triangle height 1/(res sqrt 2)), 0.55 mm at res 387;
             twist: 2 x 4 mm); Newton's particle_self_contact_margin is set to
             that, with a detection gap of half of it. Friction coefficient 0.5 (weft's static and dynamic
             friction). Newton ignores contacts between elements closer than margin + gap in the rest shape
             (particle_rest_shape_contact_exclusion_radius), since at 300K triangles the grid spacing (2.6 mm)
             is below the contact distance and a flat sheet would otherwise push itself apart.

Differences that remain (stated in the output too):
  - Material models differ. weft: Vellum-style XPBD distance constraints at 1e10 N/m (practically
    inextensible) and dihedral bending 1e-3 N m/rad. Newton VBD: StVK membrane tri_ke = tri_ka = 1e3 with
    tri_kd = 2e-4, dihedral bending edge_ke = 1e-3, edge_kd = 1e-2 (the values of Newton's own cloth_twist
    example; VBD converges poorly at 1e10). So Newton's sheet is slightly stretchier.
  - Solvers differ. weft: 20 XPBD Gauss-Seidel iterations per substep, 2 scheduled collision passes per
    substep (proximity contacts with displacement bounds, the default contact model; early passes when
    many points are cut back; impact zones). Newton: --newton-iterations VBD iterations per substep (default
    20, the same count; one VBD iteration does more work than one XPBD sweep), self-contact detected before
    and after initialization each substep (Newton's default schedule), penalty/barrier contact with
    soft_contact_ke = 1e3, soft_contact_kd = 1e-1 (Newton's cloth_twist example) and DAT truncation.
  - weft's hanging-sheet has self collision off by default (it is the solver's reference scene); both
    solvers run it with self collision (as the comparison asks; weft run --self-collision on) and without;
    --hanging-contact picks.
  - weft computes in double precision, bitwise reproducibly; Newton (Warp) in single precision.
  - Newton keeps at most 64 vertex-triangle and 128 edge-edge contact candidates per element and drops the
    rest silently (twice its defaults, as its cloth_twist example); weft's contact lists are not capped.
  - weft's times are `weft run` frames writing an HDF5 cache (the write happens after the frame's timer);
    Newton replays one CUDA graph per frame with no fences inside.

Usage: see bench/peers/README.md. CPU smoke test: newton_compare.py --quick --device cpu --weft build/openmp/bin/weft
"""
import argparse
import json
import math
import os
import platform
import re
import subprocess
import sys
import time

import numpy as np

FPS = 24.0
SUBSTEPS = 10
WEFT_ITERATIONS = 20
GRAVITY = (0.0, -9.81, 0.0)
DENSITY = 0.1
FRICTION = 0.5
DEFAULT_SIZES = [71, 224, 387]  # hanging-sheet res: 2 res^2 = 10,082 / 100,352 / 299,538 triangles
TWIST_RES = 48


def triangle_strains(x, rest, tris):
    """Each triangle's largest principal stretch - 1 (0 when compressed) against its rest shape, as weft's
    statistics measure it (constraints/triangle_strain.hpp): the same figure for both solvers' final mesh."""
    r0, r1, r2 = (rest[tris[:, k]] for k in range(3))
    e1, e2 = r1 - r0, r2 - r0
    u = e1 / np.linalg.norm(e1, axis=1)[:, None]
    n = np.cross(e1, e2)
    v = np.cross(n / np.linalg.norm(n, axis=1)[:, None], u)
    dm = np.stack([np.stack([(e1 * u).sum(1), (e2 * u).sum(1)], 1), np.stack([(e1 * v).sum(1), (e2 * v).sum(1)], 1)], 1)
    ds = np.stack([x[tris[:, 1]] - x[tris[:, 0]], x[tris[:, 2]] - x[tris[:, 0]]], 2)  # T x 3 x 2
    f = ds @ np.linalg.inv(dm)
    c = np.transpose(f, (0, 2, 1)) @ f
    a, b, d = c[:, 0, 0], c[:, 0, 1], c[:, 1, 1]
    top = (a + d) / 2 + np.sqrt(((a - d) / 2) ** 2 + b * b)
    return np.maximum(np.sqrt(top) - 1, 0)


def strain_figures(x, rest, tris):
    e = triangle_strains(np.asarray(x, dtype=np.float64), np.asarray(rest, dtype=np.float64), np.asarray(tris))
    return {"max_strain": float(e.max()), "p99_strain": float(np.quantile(e, 0.99, method="nearest"))}


def grid(res, origin, du, dv):
    """weft's io/procedural.cpp grid(): points row by row, diagonals alternating with (i + j) parity."""
    t = np.arange(res + 1) / res
    jj, ii = np.meshgrid(t, t, indexing="ij")
    x = np.asarray(origin) + ii[..., None] * np.asarray(du) + jj[..., None] * np.asarray(dv)
    tris = []
    for j in range(res):
        for i in range(res):
            a, b = j * (res + 1) + i, j * (res + 1) + i + 1
            c, d = b + res + 1, a + res + 1
            tris += [(a, b, c), (a, c, d)] if (i + j) % 2 == 0 else [(a, b, d), (b, c, d)]
    return x.reshape(-1, 3), np.asarray(tris, dtype=np.int32)


class HangingSheet:
    name = "hanging-sheet"
    frame_end = 72  # frames 1..72

    def __init__(self, res):
        self.res = res
        self.thickness = min(0.005, 0.3 / (res * math.sqrt(2.0)))  # io/builtin_scenes.cpp hanging_sheet()
        self.x, self.tris = grid(res, (-0.5, 1.0, -0.5), (1, 0, 0), (0, 0, 1))
        self.held = np.array([0, res], dtype=np.int32)

    def targets(self, f):  # f: frame index from the first frame
        return self.x[self.held]


class Twist:
    name = "twist"
    thickness = 0.004
    frame_end = 121

    def __init__(self, res):
        self.res = res
        self.x, self.tris = grid(res, (-0.5, 1.0, -0.5), (1, 0, 0), (0, 0, 1))
        held = []
        for j in range(res + 1):
            held += [j * (res + 1), j * (res + 1) + res]
        self.held = np.asarray(held, dtype=np.int32)

    def targets(self, f):
        t = min(1.0, f / 96.0)
        angle = 2 * (2 * math.pi) * t
        inward = 0.2 * min(1.0, 2 * t)
        p = self.x[self.held]
        side = np.where(p[:, 0] < 0, 1.0, -1.0)
        a = side * angle
        dy, dz = p[:, 1] - 1.0, p[:, 2]
        return np.stack([p[:, 0] + side * inward, 1.0 + dy * np.cos(a) - dz * np.sin(a),
                         dy * np.sin(a) + dz * np.cos(a)], axis=1)


def write_text(path, text):
    """Writes under a temporary name and renames when complete: a reader never sees half a file."""
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def write_obj(path, x, tris):
    write_text(path, "".join("v %.9g %.9g %.9g\n" % tuple(p) for p in x) +
               "".join("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in tris))


# ---------------------------------------------------------------------------------------------------- Newton
def run_newton(scene, frames, device, iterations, self_contact, tri_ke, out_dir):
    import warp as wp
    import newton

    @wp.kernel
    def set_pins(held: wp.array(dtype=wp.int32), a: wp.array(dtype=wp.vec3), b: wp.array(dtype=wp.vec3),
                 s: float, q0: wp.array(dtype=wp.vec3), q1: wp.array(dtype=wp.vec3)):
        k = wp.tid()
        p = a[k] + s * (b[k] - a[k])
        q0[held[k]] = p
        q1[held[k]] = p

    margin = 2 * scene.thickness
    gap = 0.5 * margin
    settings = {
        "substeps": SUBSTEPS, "iterations": iterations, "fps": FPS, "density": DENSITY, "tri_ke": tri_ke,
        "tri_ka": tri_ke, "tri_kd": 2e-4, "edge_ke": 1e-3, "edge_kd": 1e-2, "self_contact": self_contact,
        "self_contact_margin": margin, "self_contact_gap": gap, "rest_exclusion": margin + gap,
        "soft_contact_ke": 1e3, "soft_contact_kd": 1e-1, "mu": FRICTION,
    }
    t_setup = time.perf_counter()
    with wp.ScopedDevice(device):
        builder = newton.ModelBuilder(up_axis=newton.Axis.Y, gravity=GRAVITY)
        builder.add_cloth_mesh(pos=wp.vec3(0.0, 0.0, 0.0), rot=wp.quat_identity(), scale=1.0, vel=wp.vec3(0.0, 0.0, 0.0),
                               vertices=[wp.vec3(*p) for p in scene.x], indices=scene.tris.reshape(-1).tolist(),
                               density=DENSITY, tri_ke=tri_ke, tri_ka=tri_ke, tri_kd=2e-4, edge_ke=1e-3, edge_kd=1e-2,
                               particle_radius=scene.thickness)
        builder.color()
        model = builder.finalize()
        model.soft_contact_ke, model.soft_contact_kd, model.soft_contact_mu = 1e3, 1e-1, FRICTION
        flags = model.particle_flags.numpy()
        flags[scene.held] &= ~int(newton.ParticleFlags.ACTIVE)
        model.particle_flags = wp.array(flags, dtype=model.particle_flags.dtype)
        kw = {}
        if self_contact:
            kw = dict(particle_self_contact_margin=margin, particle_self_contact_gap=gap,
                      particle_rest_shape_contact_exclusion_radius=margin + gap,
                      particle_vertex_contact_buffer_size=64, particle_edge_contact_buffer_size=128)
        solver = newton.solvers.SolverVBD(model, iterations=iterations, particle_enable_self_contact=self_contact, **kw)
        s0, s1, control = model.state(), model.state(), model.control()
        held = wp.array(scene.held, dtype=wp.int32)
        ta = wp.array(scene.targets(0), dtype=wp.vec3)
        tb = wp.array(scene.targets(0), dtype=wp.vec3)
        dt = 1.0 / FPS / SUBSTEPS

        def frame():
            nonlocal s0, s1
            if self_contact:
                solver.rebuild_bvh(s0)
            for k in range(SUBSTEPS):
                s0.clear_forces()
                wp.launch(set_pins, dim=len(scene.held), inputs=[held, ta, tb, (k + 1) / SUBSTEPS, s0.particle_q, s1.particle_q])
                solver.step(s0, s1, control, None, dt)
                s0, s1 = s1, s0

        use_graph = wp.get_device().is_cuda and SUBSTEPS % 2 == 0
        graph = None
        times = []
        for f in range(frames):
            ta.assign(scene.targets(f).astype(np.float32))
            tb.assign(scene.targets(f + 1).astype(np.float32))
            wp.synchronize_device()
            t0 = time.perf_counter()
            if graph is not None:
                wp.capture_launch(graph)
            else:
                frame()
                if use_graph:  # after the uncaptured warm-up frame (kernels compiled, buffers allocated)
                    try:
                        with wp.ScopedCapture() as cap:
                            frame()
                        graph = cap.graph
                    except Exception as e:  # noqa: BLE001 - a solver that cannot be captured runs uncaptured
                        print("  (no CUDA graph: %s)" % e, flush=True)
                        use_graph = False
            wp.synchronize_device()
            times.append(time.perf_counter() - t0)
            if f == 0:
                setup_s = time.perf_counter() - t_setup
        x = s0.particle_q.numpy().astype(np.float64)
    obj = os.path.join(out_dir, "newton_%s_%d_contact-%s.obj" % (scene.name, scene.res, "on" if self_contact else "off"))
    write_obj(obj, x, scene.tris)
    timed = times[1:] if len(times) > 1 else times
    return {
        "ms_per_frame": 1e3 * sum(timed) / len(timed), "frames_timed": len(timed), "first_frame_s": times[0],
        "setup_and_first_frame_s": setup_s, "cuda_graph": graph is not None, "finite": bool(np.isfinite(x).all()),
        "lowest_y": float(x[:, 1].min()), "pin_error": float(np.abs(x[scene.held] - scene.targets(frames)).max()),
        "obj": obj, "settings": settings, **strain_figures(x, scene.x, scene.tris),
    }


# ------------------------------------------------------------------------------------------------------ weft
def weft_cmd(args, *rest):
    cmd = [args.weft, "--backend", args.weft_backend] + (["--threads", str(args.threads)] if args.threads else [])
    return cmd + [str(r) for r in rest]


def sh(cmd):
    print("  $", " ".join(cmd), flush=True)
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s failed (%d):\n%s" % (" ".join(cmd), r.returncode, r.stdout))
    return r.stdout


def last_count(output):
    m = re.findall(r"^intersections (\d+)$", output, re.M)
    return int(m[-1]) if m else None


def run_weft(args, scene, frames, self_collision, out_dir):
    """One `weft run` writing a cache (ms per frame from its per-frame lines, the first stepped frame being
    warm-up), then `weft check-intersections CACHE --all-frames` on that cache: the scene is simulated once."""
    on = "on" if self_collision else "off"
    cache = os.path.join(out_dir, "weft_%s_%d_self-%s.h5" % (scene.name, scene.res, on))
    out = sh(weft_cmd(args, "run", "builtin:" + scene.name, "--res", scene.res, "--frames", "1-%d" % (1 + frames),
                      "--self-collision", on, *(["--contact-solver", args.contact_solver] if args.contact_solver else []),
                      *args.weft_arg, "-o", cache))
    ms = [float(v) for v in re.findall(r"^frame \d+ .* ([0-9.]+) ms$", out, re.M)]
    head = re.search(r"^\S+: \d+ points, (\d+) triangles", out, re.M)
    timed = ms[1:] if len(ms) > 1 else ms
    chk = sh(weft_cmd(args, "check-intersections", cache, "--all-frames"))
    per_frame = [int(v) for v in re.findall(r"^frame \d+ .*intersections (\d+)$", chk, re.M)]
    settings = sh(weft_cmd(args, "info", cache))
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reports"))
    import weftlib  # noqa: E402 - the cache reader of the report scripts
    final = np.asarray(weftlib.read_cache(cache)["positions"][-1], dtype=np.float64)
    return {**strain_figures(final, scene.x, scene.tris), "weft_args": list(args.weft_arg),
        "lowest_y": float(final[:, 1].min()), "pin_error": float(np.abs(final[scene.held] - scene.targets(frames)).max()),
        "ms_per_frame": sum(timed) / len(timed) if timed else None, "frames_timed": len(timed),
        "intersections": per_frame[-1] if per_frame else last_count(chk),
        "max_intersections_any_frame": max(per_frame) if per_frame else None,
        "weft_triangles": int(head[1]) if head else None, "backend": args.weft_backend,
        "settings": {"substeps": SUBSTEPS, "iterations": WEFT_ITERATIONS, "collision_passes": 2 if self_collision else 0,
                     "fps": FPS, "density": DENSITY, "stretch": "distance 1e10 N/m", "bend": "1e-3 N m/rad",
                     "self_collision": self_collision, "thickness": scene.thickness, "friction": FRICTION,
                     "cache_info": settings.strip().splitlines()[:12]},
    }


def count_obj(args, obj):
    return last_count(sh(weft_cmd(args, "check-intersections", obj))) if args.weft else None


# ------------------------------------------------------------------------------------------------------ main
def table(rows):
    head = ("| scene | triangles | solver | ms/frame | max / p99 strain (final) | frames timed | intersections (final) | settings |\n"
            "|---|---:|---|---:|---|---:|---:|---|\n")
    body = ""
    for r in rows:
        st = r["settings"]
        brief = "%d substeps x %d iter" % (st["substeps"], st["iterations"])
        if r["solver"].startswith("newton"):
            brief += ", self-contact %s" % ("on" if st["self_contact"] else "off")
            brief += ", lowest y %.3f m, pin error %.1e m" % (r["lowest_y"], r["pin_error"])
            brief += "" if r["finite"] else ", NOT FINITE"
        else:
            brief += ", %d collision passes, self collision %s" % (st["collision_passes"], "on" if st["self_collision"] else "off")
            brief += ", lowest y %.3f m, pin error %.1e m" % (r["lowest_y"], r["pin_error"])
            brief += ", max intersections over frames %s" % r["max_intersections_any_frame"]
            brief += "".join(" " + a for a in r.get("weft_args", []))
        inter = "-" if r["intersections"] is None else str(r["intersections"])
        body += "| %s | %d | %s | %.2f | %.3g / %.3g | %d | %s | %s |\n" % (
            r["scene"], r["triangles"], r["solver"], r["ms_per_frame"], r["max_strain"], r["p99_strain"],
            r["frames_timed"], inter, brief)
    return head + body


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--weft", help="path to the weft binary (without it only Newton runs and nothing is counted)")
    ap.add_argument("--weft-backend", default=None, help="cuda | openmp | serial (default: cuda on a CUDA device)")
    ap.add_argument("--threads", type=int, default=0, help="weft --threads (OpenMP)")
    ap.add_argument("--device", default=None, help="Warp device for Newton: cuda:0 (default when present) or cpu")
    ap.add_argument("--sizes", default=None, help="hanging-sheet resolutions, comma-separated (default 71,224,387: "
                    "about 10K, 100K, 300K triangles)")
    ap.add_argument("--twist-res", type=int, default=None, help="twist resolution (default %d, weft's)" % TWIST_RES)
    ap.add_argument("--scenes", default="hanging-sheet,twist")
    ap.add_argument("--frames", type=int, default=None, help="frames stepped (default: the scene's whole range, "
                    "71 for hanging-sheet and 120 for twist); the first is warm-up")
    ap.add_argument("--newton-iterations", type=int, default=WEFT_ITERATIONS, help="VBD iterations per substep")
    ap.add_argument("--tri-ke", type=float, default=1e3, help="Newton membrane stiffness tri_ke = tri_ka")
    ap.add_argument("--hanging-contact", choices=["both", "on", "off"], default="both",
                    help="self collision on the hanging sheet, both solvers (weft's scene default: off)")
    ap.add_argument("--quick", action="store_true", help="CPU smoke test: hanging res 10, twist res 10, 4 frames")
    ap.add_argument("--contact-solver", choices=["gauss-seidel", "jacobi"], default=None,
                    help="weft --contact-solver (default: the scene's, Gauss-Seidel)")
    ap.add_argument("--weft-arg", action="append", default=[], metavar="ARG",
                    help="an extra argument for weft run, repeated for each (e.g. --weft-arg=--tethers --weft-arg=1)")
    ap.add_argument("--skip-newton", action="store_true")
    ap.add_argument("--skip-weft", action="store_true", help="run only Newton (--weft still counts its intersections)")
    ap.add_argument("--out", default="peer-results", help="folder for results.json and results.md")
    ap.add_argument("--work", default=None, help="folder for the meshes and weft's caches (default: --out)")
    args = ap.parse_args()

    if args.quick:
        sizes, twist_res, frames = [10], 10, 4
    else:
        sizes, twist_res, frames = DEFAULT_SIZES, TWIST_RES, None
    if args.sizes:
        sizes = [int(s) for s in args.sizes.split(",")]
    if args.twist_res:
        twist_res = args.twist_res
    if args.frames:
        frames = args.frames
    work = args.work or args.out
    os.makedirs(args.out, exist_ok=True)
    os.makedirs(work, exist_ok=True)

    device = args.device
    wp_version = newton_version = None
    if not args.skip_newton:
        import warp as wp
        import newton
        wp.config.quiet = True  # no per-module load lines
        wp.init()
        device = device or ("cuda:0" if wp.is_cuda_available() else "cpu")
        wp_version, newton_version = wp.__version__, newton.__version__
    if args.weft_backend is None:
        args.weft_backend = "cuda" if (device or "").startswith("cuda") else "openmp"

    scenes = []
    names = args.scenes.split(",")
    if "hanging-sheet" in names:
        scenes += [HangingSheet(r) for r in sizes]
    if "twist" in names:
        scenes.append(Twist(twist_res))

    rows = []
    for sc in scenes:
        n = frames or (sc.frame_end - 1)
        tri = len(sc.tris)
        print("%s res %d: %d triangles, %d frames" % (sc.name, sc.res, tri, n), flush=True)
        modes = [sc.name != "hanging-sheet" or args.hanging_contact != "off"]
        if sc.name == "hanging-sheet" and args.hanging_contact == "both":
            modes = [True, False]
        for contact in modes if args.weft and not args.skip_weft else []:
            w = run_weft(args, sc, n, contact, work)
            if w.pop("weft_triangles") != tri:
                raise SystemExit("weft's %s has other triangles than this script's (%d)" % (sc.name, tri))
            rows.append(dict(scene=sc.name, res=sc.res, triangles=tri, solver="weft (%s)" % w["backend"], **w))
            print("  weft (self collision %s): %.2f ms/frame, %s intersections" % (
                "on" if contact else "off", w["ms_per_frame"], w["intersections"]), flush=True)
        if not args.skip_newton:
            for contact in modes:
                r = run_newton(sc, n, device, args.newton_iterations, contact, args.tri_ke, work)
                r["intersections"] = count_obj(args, r["obj"])
                rows.append(dict(scene=sc.name, res=sc.res, triangles=tri, solver="newton-vbd (%s)" % device, **r))
                print("  newton (self-contact %s): %.2f ms/frame, %s intersections, first frame %.1f s" % (
                    "on" if contact else "off", r["ms_per_frame"], r["intersections"], r["first_frame_s"]), flush=True)

    meta = {"device": device, "weft_backend": args.weft_backend, "warp": wp_version, "newton": newton_version,
            "host": platform.node(), "python": platform.python_version(),
            "notes": __doc__[__doc__.index("How weft's"):__doc__.index("Usage:")].strip()}
    if wp_version and device.startswith("cuda"):
        import warp as wp
        meta["gpu"] = wp.get_device(device).name
    write_text(os.path.join(args.out, "results.json"), json.dumps({"meta": meta, "rows": rows}, indent=1))
    md = "# weft vs Newton VBD\n\nNewton %s, Warp %s, device %s%s, weft backend %s.\n\n%s\n```\n%s\n```\n" % (
        newton_version, wp_version, device, " (%s)" % meta.get("gpu") if meta.get("gpu") else "", args.weft_backend,
        table(rows), meta["notes"])
    write_text(os.path.join(args.out, "results.md"), md)
    print(table(rows))


if __name__ == "__main__":
    sys.exit(main())
