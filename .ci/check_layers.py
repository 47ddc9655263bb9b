#!/usr/bin/env python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""Fails when an include points up: a layer of the core that includes a
layer listed above it, or core/ that includes anything of proto/, server/ or
client/. The layers, bottom up, are the README's "Architecture" section.

Usage: .ci/check_layers.py [--list]   (--list prints each file's layer)
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent

# Bottom up. Each layer: its folders under core/src (and core/tetgen) and
# its public headers under core/include/dot. core/tetgen (TetGen, apart
# for its licence) is a search-space backend.
LAYERS = [
    ("base", ["util"],
     ["status.h", "geometry.h", "elapsed.h", "mesh.h", "control.h",
      "table_memory.h"]),
    ("vocabulary", [], ["metrics.h", "problem.h"]),
    ("mesh", ["mesh"], ["validate.h"]),
    ("polygon", ["polygon"], []),
    ("search_space", ["search_space", "tetgen"], []),
    ("solve", ["solve"], ["space_cache.h"]),
    ("triangulate", ["triangulate"], ["triangulate.h"]),
    ("mesh_io", ["mesh_io"], ["io.h", "mesh_repair.h"]),
    ("fill", ["fill"], ["fill_holes.h", "fill_soup.h"]),
    ("network", ["network"], ["network.h"]),
    ("samples", ["samples"], ["curves.h", "hole_generator.h", "network_samples.h"]),
    ("helpers", ["helpers"], ["delaunay_helpers.h"]),
    ("umbrella", [], ["dot.h"]),
]

CORE = ROOT / "core"
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def layer_of_header(include):
    """The layer of a quoted include as core code writes it."""
    if include.startswith("dot/"):
        name = include[len("dot/"):]
        for rank, (_, _, headers) in enumerate(LAYERS):
            if name in headers:
                return rank
        return None
    folder = include.split("/")[0]
    for rank, (_, folders, _) in enumerate(LAYERS):
        if folder in folders:
            return rank
    return None


def layer_of_file(path):
    rel = path.relative_to(CORE)
    if rel.parts[0] == "include":
        return layer_of_header("dot/" + rel.name)
    if rel.parts[0] == "tetgen":
        return layer_of_header("tetgen/x")
    if rel.parts[0] == "src" and len(rel.parts) > 2:
        return layer_of_header(rel.parts[1] + "/x")
    return None


def main():
    problems = []
    files = sorted(p for p in CORE.rglob("*")
                   if p.suffix in (".h", ".cc") and "tetgen.h" != p.name)
    for path in files:
        rel = path.relative_to(ROOT)
        rank = layer_of_file(path)
        if rank is None:
            problems.append(f"{rel}: in no layer (add its folder to LAYERS)")
            continue
        if "--list" in sys.argv:
            print(f"{LAYERS[rank][0]:13} {rel}")
        text = path.read_text(encoding="utf-8")
        for include in INCLUDE.findall(text):
            if include.split("/")[0] in ("proto", "server", "client", "wire"):
                problems.append(f"{rel}: includes {include}: core/ knows "
                                "nothing of the wire, the server or clients")
                continue
            if include == "tetgen.h":
                continue
            target = layer_of_header(include)
            if target is None:
                problems.append(f"{rel}: includes {include}, in no layer")
            elif target > rank:
                problems.append(
                    f"{rel} ({LAYERS[rank][0]}) includes {include} "
                    f"({LAYERS[target][0]}), a layer above it")
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        print(f"check_layers: {len(problems)} include(s) point up",
              file=sys.stderr)
        return 1
    print(f"check_layers: {len(files)} files, every include points down")
    return 0


if __name__ == "__main__":
    sys.exit(main())
