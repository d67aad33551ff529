#!/usr/bin/env python3
"""`weft export cache.h5 --format usd OUT` end to end: a tiny cache exported as .usda, .usdc and .usd, each read
back with OpenUSD's Python (usd-core) and checked against the cache read with h5py.

    python3 tests/usd_export.py --weft build/openmp/bin/weft

Checks: the stage opens; /cloth is its default prim and a UsdGeom.Mesh; points and velocities are sampled at
exactly the cache's frames and equal its doubles rounded to float32; extent is each frame's bounds;
faceVertexCounts are all 3 and faceVertexIndices the cache's /triangles; timeCodesPerSecond and
framesPerSecond are the cache's fps, start/end the frame range, Y up, metres; --frames picks a sub-range; each
file is of the format its extension names; a bad extension and an unwritable output fail cleanly, leaving no
temporary file. Exits 77 (CTest's skip) when Python lacks usd-core, h5py or numpy, or weft was built without
USD; scripts/setup.sh installs them all.
"""
import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

SKIP = 77

try:
    import h5py
    import numpy as np
    from pxr import Sdf, Usd, UsdGeom
except ImportError as e:
    print(f"skip: {e} (pip install usd-core h5py numpy)")
    sys.exit(SKIP)


def check(ok, what):
    if not ok:
        sys.exit(f"FAIL {what}")


def weft(exe, *args, expect=0):
    r = subprocess.run([exe, *map(str, args)], capture_output=True, text=True,
                       env={**os.environ, "OMP_PROC_BIND": "false"})
    if expect is not None and r.returncode != expect:
        sys.exit(f"FAIL weft {' '.join(map(str, args))}: exit {r.returncode}, expected {expect}\n"
                 f"{r.stdout}\n{r.stderr}")
    return r


def check_stage(path, cache, frames):
    """The USD file at `path` against the cache's stored frames `frames` (frame numbers)."""
    what = path.name
    stage = Usd.Stage.Open(str(path))
    check(stage is not None, f"{what}: Usd.Stage.Open")
    prim = stage.GetPrimAtPath("/cloth")
    check(prim.IsValid() and prim.IsA(UsdGeom.Mesh), f"{what}: /cloth is a UsdGeom.Mesh")
    check(stage.GetDefaultPrim().GetPath() == Sdf.Path("/cloth"), f"{what}: default prim /cloth")
    fps = float(cache["settings"].attrs["fps"])
    check(stage.GetTimeCodesPerSecond() == fps, f"{what}: timeCodesPerSecond {stage.GetTimeCodesPerSecond()} != {fps}")
    check(stage.GetFramesPerSecond() == fps, f"{what}: framesPerSecond {stage.GetFramesPerSecond()} != {fps}")
    check((stage.GetStartTimeCode(), stage.GetEndTimeCode()) == (frames[0], frames[-1]),
          f"{what}: time codes {stage.GetStartTimeCode()}-{stage.GetEndTimeCode()}, expected {frames[0]}-{frames[-1]}")
    check(UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.y, f"{what}: up axis {UsdGeom.GetStageUpAxis(stage)}")
    check(UsdGeom.GetStageMetersPerUnit(stage) == 1.0, f"{what}: metersPerUnit {UsdGeom.GetStageMetersPerUnit(stage)}")

    mesh = UsdGeom.Mesh(prim)
    tris = cache["triangles"][:]
    counts = np.array(mesh.GetFaceVertexCountsAttr().Get())
    check(len(counts) == len(tris) and (counts == 3).all(), f"{what}: faceVertexCounts are {len(tris)} threes")
    indices = np.array(mesh.GetFaceVertexIndicesAttr().Get())
    check(np.array_equal(indices, tris.reshape(-1)), f"{what}: faceVertexIndices are the cache's /triangles")
    check(mesh.GetSubdivisionSchemeAttr().Get() == UsdGeom.Tokens.none, f"{what}: subdivisionScheme none")
    check(mesh.GetOrientationAttr().Get() == UsdGeom.Tokens.rightHanded, f"{what}: orientation rightHanded")

    stored = list(cache["frames"][:])
    for name, attr, data in (("points", mesh.GetPointsAttr(), cache["positions"]),
                             ("velocities", mesh.GetVelocitiesAttr(), cache["velocities"])):
        check(str(attr.GetTypeName()) == {"points": "point3f[]", "velocities": "vector3f[]"}[name],
              f"{what}: {name} is {attr.GetTypeName()}")
        times = attr.GetTimeSamples()
        check(times == [float(f) for f in frames], f"{what}: {name} sampled at {times}, expected {frames}")
        for f in frames:
            exact = data[stored.index(f)]
            got = np.array(attr.Get(f), dtype=np.float32)
            check(got.shape == exact.shape, f"{what}: {name} at {f}: shape {got.shape}, expected {exact.shape}")
            check(np.array_equal(got, exact.astype(np.float32)), f"{what}: {name} at {f} are the cache's, as float32")
            check(np.allclose(got, exact, rtol=1e-6, atol=1e-6), f"{what}: {name} at {f} within float precision")
            if name == "points":
                extent = np.array(mesh.GetExtentAttr().Get(f))
                check(np.array_equal(extent, [got.min(axis=0), got.max(axis=0)]), f"{what}: extent at {f}")
    layer = stage.GetRootLayer()
    check(layer.customLayerData["weft"]["scene"] == cache.attrs["scene"], f"{what}: customLayerData weft.scene")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--weft", required=True, help="the weft binary")
    exe = ap.parse_args().weft
    with tempfile.TemporaryDirectory(prefix="weft-usd-") as tmp:
        tmp = Path(tmp)
        weft(exe, "run", "builtin:hanging-sheet", "--res", 4, "--frames", "1-5", "-o", tmp / "c.h5", "--quiet")
        out = tmp / "usd"
        r = weft(exe, "export", tmp / "c.h5", "--format", "usd", out / "c.usda", expect=None)
        if r.returncode == 2 and "built without USD" in r.stderr:
            print(f"skip: {r.stderr.strip()}")
            return SKIP
        check(r.returncode == 0, f"export c.usda: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
        check("wrote frames 1-5 to" in r.stdout, f"export c.usda says what it wrote: {r.stdout!r}")
        weft(exe, "export", tmp / "c.h5", "--format", "usd", out / "c.usdc")
        weft(exe, "export", tmp / "c.h5", "--format", "usd", out / "c.usd")
        weft(exe, "export", tmp / "c.h5", "--format", "usd", out / "part.usda", "--frames", "2-4")

        check((out / "c.usda").read_bytes().startswith(b"#usda 1.0"), "c.usda is text")
        for name in ("c.usdc", "c.usd"):  # .usd: OpenUSD's default, the binary crate format
            check((out / name).read_bytes().startswith(b"PXR-USDC"), f"{name} is a crate (binary) file")
        with h5py.File(tmp / "c.h5", "r") as cache:
            check(list(cache["frames"][:]) == [1, 2, 3, 4, 5], "the cache holds frames 1-5")
            for name in ("c.usda", "c.usdc", "c.usd"):
                check_stage(out / name, cache, [1, 2, 3, 4, 5])
            check_stage(out / "part.usda", cache, [2, 3, 4])

        # Failures: exit non-zero naming the file, and leave no temporary behind.
        r = weft(exe, "export", tmp / "c.h5", "--format", "usd", out / "c.abc", expect=2)
        check("c.abc" in r.stderr and ".usda" in r.stderr, f"a bad extension is named: {r.stderr!r}")
        (out / "taken.usda").mkdir()  # a folder where the file should go: the final rename fails
        r = weft(exe, "export", tmp / "c.h5", "--format", "usd", out / "taken.usda", expect=1)
        check("cannot write" in r.stderr and "taken.usda" in r.stderr, f"an unwritable output is named: {r.stderr!r}")
        left = sorted(p.name for p in out.iterdir())
        check(left == ["c.usd", "c.usda", "c.usdc", "part.usda", "taken.usda"], f"no temporary files left: {left}")
    print("usd_export: .usda, .usdc and .usd read back with usd-core equal the cache (float32)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
