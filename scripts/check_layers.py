#!/usr/bin/env python3
"""Keeps weft's layers (docs/architecture.md, "Folders, bottom to top"): a source in a layered folder includes
its own folder and folders on lower levels only, never one on its level or above. Prints every include that
breaks this as FILE:LINE and exits 1; ctest runs it as the test `layers`.

    scripts/check_layers.py [SOURCE_DIR]    (default: the checkout this script is in)
"""
import re
import sys
from pathlib import Path

# Bottom to top; folders on one level are independent of each other.
LEVELS = [
    ["core"],
    ["scene"],
    ["constraints", "collision"],
    ["solver"],
    ["backends"],
    ["io"],
    ["farm"],
    ["apps"],
]
# Above every level: they may use all of it, and nothing in the layers may include them.
USERS = ["bench", "examples", "tests"]
SOURCES = {".hpp", ".cpp", ".h", ".in"}
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent)
    level = {folder: k for k, folders in enumerate(LEVELS) for folder in folders}
    level.update({folder: len(LEVELS) for folder in USERS})
    errors = []
    for top in sorted(p for p in root.iterdir() if p.is_dir() and not p.name.startswith(".")):
        if top.name in ("build", "cmake", "docs", "scripts", "shared"):
            continue
        files = sorted(p for p in top.rglob("*") if p.suffix in SOURCES and p.is_file())
        if files and top.name not in level:
            errors.append(f"{top.name}/: a folder of sources on no level: add it to LEVELS or USERS in scripts/check_layers.py")
        if top.name not in level or top.name in USERS:
            continue
        for path in files:
            for n, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                m = INCLUDE.match(line)
                if not m or "/" not in m.group(1):
                    continue  # the generated weft_version.hpp, beside the folders
                folder = m.group(1).split("/", 1)[0]
                where = f"{path.relative_to(root)}:{n}"
                if folder not in level:
                    errors.append(f"{where}: includes {m.group(1)}, of a folder on no level")
                elif folder != top.name and level[folder] >= level[top.name]:
                    side = "beside" if level[folder] == level[top.name] else "above"
                    errors.append(f"{where}: {top.name}/ includes {m.group(1)}, {side} it")
    for e in errors:
        print(e)
    if errors:
        print(f"layers: {len(errors)} include(s) out of order (docs/architecture.md, \"Folders, bottom to top\")")
        return 1
    print("layers: " + " < ".join(" ".join(f"{f}/" for f in folders) for folders in LEVELS))
    return 0


if __name__ == "__main__":
    sys.exit(main())
