#!/usr/bin/python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""A scan with colours and UVs through `dotctl fill-holes --local`.

Makes the scan from a libcgal-demo mesh: holes cut by `dotctl generate
holes`, then per-vertex colours and per-corner UVs that are smooth
functions of position (the UVs a spherical map around the centroid, with a
seam where the longitude wraps: faces across it get u + 1 on their far
corners). Fills it to OBJ and to PLY and checks, against those functions:
every input vertex keeps its colour exactly (PLY: to a byte), every new
vertex has one (interpolated: its error is printed), every new face has UVs
(none spans the seam away from the map's poles: the seam runs on through
the patches) and its area
in UV space is not zero.

Usage: bench/attribute_scan.py DOTCTL MESH.off [HOLES] [FACES_PER_HOLE]
Exits 1 when a check fails; prints the figures.
"""
import math
import os
import subprocess
import sys
import tempfile

import numpy as np


def read_off(path):
    words = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].split()
            words.extend(line)
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    at = 4
    v = np.array(words[at : at + 3 * nv], dtype=float).reshape(nv, 3)
    at += 3 * nv
    faces = []
    for _ in range(nf):
        k = int(words[at])
        faces.append([int(x) for x in words[at + 1 : at + 1 + k]])
        at += 1 + k
    return v, faces


def colour(p, lo, hi):
    """A smooth colour field over the box [lo, hi]."""
    t = (p - lo) / (hi - lo)
    return np.clip(0.5 + 0.5 * np.sin(2.0 * t * np.array([2.0, 3.0, 5.0])), 0, 1)


def longitude_latitude(p, centre):
    d = p - centre
    u = (math.atan2(d[1], d[0]) + math.pi) / (2 * math.pi)
    r = max(np.linalg.norm(d), 1e-12)
    v = math.acos(max(-1.0, min(1.0, d[2] / r))) / math.pi
    return u, v


def write_scan_obj(path, v, faces, lo, hi, centre):
    with open(path, "w") as f:
        for p in v:
            c = colour(p, lo, hi)
            f.write("v %.17g %.17g %.17g %.9g %.9g %.9g\n" % (*p, *c))
        n = 0
        lines = []
        for face in faces:
            uv = [longitude_latitude(v[i], centre) for i in face]
            us = [u for u, _ in uv]
            if max(us) - min(us) > 0.5:  # across the seam: one chart
                uv = [(u + 1 if u < 0.5 else u, t) for u, t in uv]
            corners = []
            for i, (u, t) in zip(face, uv):
                f.write("vt %.9g %.9g\n" % (u, t))
                n += 1
                corners.append("%d/%d" % (i + 1, n))
            lines.append("f " + " ".join(corners) + "\n")
        f.writelines(lines)


def read_obj(path):
    v, c, vt, faces = [], [], [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                v.append([float(x) for x in w[1:4]])
                c.append([float(x) for x in w[4:7]])
            elif w[0] == "vt":
                vt.append([float(x) for x in w[1:3]])
            elif w[0] == "f":
                faces.append([tuple(int(x) - 1 for x in k.split("/")[:2]) for k in w[1:]])
    return np.array(v), np.array(c), np.array(vt), faces


def read_ascii_ply(path):
    with open(path) as f:
        header = []
        for line in f:
            header.append(line.split())
            if line.startswith("end_header"):
                break
        nv = int(next(h[2] for h in header if h[:2] == ["element", "vertex"]))
        props = [h[2] for h in header if h[0] == "property" and h[1] != "list"]
        rows = [f.readline().split() for _ in range(nv)]
    table = np.array(rows, dtype=float)
    col = {name: k for k, name in enumerate(props[: table.shape[1]])}
    return table, col


def main():
    dotctl, mesh = sys.argv[1], sys.argv[2]
    holes = sys.argv[3] if len(sys.argv) > 3 else "12"
    per_hole = sys.argv[4] if len(sys.argv) > 4 else "60"
    failed = []

    def check(ok, what):
        if not ok:
            failed.append(what)
            print("FAILED:", what)

    with tempfile.TemporaryDirectory() as work:
        holey = os.path.join(work, "holey.off")
        subprocess.run([dotctl, "generate", "holes", "-k", holes, "-t", per_hole,
                        "--seed", "7", mesh, "-o", holey], check=True,
                       stdout=subprocess.DEVNULL)
        v, faces = read_off(holey)
        lo, hi, centre = v.min(axis=0), v.max(axis=0), v.mean(axis=0)
        scan = os.path.join(work, "scan.obj")
        write_scan_obj(scan, v, faces, lo, hi, centre)
        out_obj = os.path.join(work, "filled.obj")
        out_ply = os.path.join(work, "filled.ply")
        for out, extra in ((out_obj, []), (out_ply, ["--ascii"])):
            r = subprocess.run([dotctl, "fill-holes", "--local", scan, "-o", out] + extra,
                               capture_output=True, text=True)
            print(r.stdout.strip().splitlines()[-1] if r.stdout.strip() else r.stderr)
            check(r.returncode == 0, "fill-holes exit %d: %s" % (r.returncode, r.stderr))
            check("dropped" not in r.stdout, "an attribute was dropped: " + r.stdout)
        ov, oc, ovt, ofaces = read_obj(out_obj)
        n = len(v)
        check(np.array_equal(ov[:n], v), "input vertices kept exactly")
        check(np.allclose(oc[:n], [colour(p, lo, hi) for p in v], atol=1e-6),
              "input colours kept")
        new = ov[n:]
        err = np.abs(oc[n:] - np.array([colour(p, lo, hi) for p in new])) if len(new) else np.zeros((0, 3))
        check(len(new) > 0, "the fill added vertices")
        check(bool(np.all((oc >= 0) & (oc <= 1))), "colours in [0, 1]")
        spans, zero_area, new_faces = 0, 0, 0
        input_faces = len(faces)
        for face in ofaces[input_faces:]:
            new_faces += 1
            uv = np.array([ovt[t] for _, t in face])
            # Near the poles the spherical map itself is singular (input
            # faces span every longitude there): the seam is checked away
            # from them.
            near_pole = min(uv[:, 1]) < 0.1 or max(uv[:, 1]) > 0.9
            if np.ptp(uv[:, 0]) > 0.5 and not near_pole:
                spans += 1
            a = uv[1] - uv[0]
            b = uv[2] - uv[0]
            if abs(a[0] * b[1] - a[1] * b[0]) == 0:
                zero_area += 1
        check(spans == 0, "%d new faces span the UV seam" % spans)
        check(zero_area == 0, "%d new faces have no area in UV space" % zero_area)
        table, col = read_ascii_ply(out_ply)
        for name in ("red", "green", "blue", "s", "t"):
            check(name in col, "PLY has property " + name)
        print("scan: %d vertices, %d faces, %s holes of %s faces; new: %d vertices, "
              "%d faces" % (n, input_faces, holes, per_hole, len(new), new_faces))
        print("colour of new vertices against the field: mean error %.4f, max %.4f"
              % (err.mean() if err.size else 0, err.max() if err.size else 0))
        print("new faces spanning the UV seam: %d; with zero UV area: %d" % (spans, zero_area))
    if failed:
        sys.exit(1)


if __name__ == "__main__":
    main()
