#!/usr/bin/python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""Records the golden streams of tests/golden/ (run once; commit).

Starts build/server/dot-server on a loopback port with 1 KiB mesh chunks
(--chunk-kb 1, so small meshes still come back in several messages) and
records, byte for byte, the response streams of four calls:

- triangulate.stream: one Triangulate call (a noisy 80-vertex saddle rim
  with edge protection, so the server inserts vertices, and with
  omit_input_vertices, so the client must put the input back);
- triangulate_loops.stream: one Triangulate call with three loops (a
  pants: Summary.loop_sizes, loop and bridges);
- fill_holes.stream: one FillHoles call answering the whole mesh (a small
  sphere with a hole, filled to the fair stage);
- fill_holes_patches.stream: one FillHoles call answering patches
  (FILL_ANSWER_PATCHES) for a bumpy grid whose hole needs edge protection
  (a face beside it is split: a replaced face) and whose faired patch (61
  new vertices, density 4) continues over several 1 KiB messages; its rim
  is left open (skip_longest).

Each stream is written as length-prefixed serialized messages (4-byte
little-endian length, then the bytes): triangulate.stream holds
dot.v1.TriangulateResponse messages, the fill streams
dot.v1.FillHolesResponse messages. The FillHoles uploads are recorded too
(fill_holes.requests, fill_holes_patches.requests: the
dot.v1.FillHolesRequest messages sent, made by dot_client.wire.fill_requests
in 1 KiB messages), so the C++ FillRequestWriter can be held to the same
messages.

The expected results beside them (*.json) do not come from any stream
reassembly: they are what `dotctl ... --local` computes in-process (the
core library, no wire), written with 17 significant digits, so exact. The
expected patches are derived from dotctl's whole filled mesh and its
report, by the layout the README documents for the result ("The result":
input vertices first, then each hole's new vertices; input faces keep
their index, a face split by edge protection is replaced in place by its
first piece and its other pieces are appended, then each hole's patch):
the hole's new vertices are the `boundary_inserted + refined_vertices`
after the input's, its faces the last `patch_triangles`, and the split
face's replacement its piece in place followed by the appended pieces
(the recording has one split face, so the appended pieces are all its
own). Before anything is written, the Python reassembly of each stream
must give the expected result. The C++ test (tests/client/
golden_stream_test.cc) and the Python test (tests/python/test_golden.py)
replay the streams through their reassembly code and must get the same.

Usage: PYTHONPATH=build/client/python scripts/record_golden.py
       [--server build/server/dot-server] [--dotctl build/client/dotctl]
       [--out tests/golden] [--only triangulate fill_holes ...]
"""
import argparse
import json
import os
import socket
import subprocess
import sys
import tempfile
import time

import grpc
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "build", "client", "python"))
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))

import dot_client  # noqa: E402
from dot_client import wire  # noqa: E402
from dot_client._proto.dot.v1 import triangulation_pb2 as pb  # noqa: E402
from shapes import bumpy_grid_with_hole  # noqa: E402

GOLDEN = ["triangulate", "triangulate_loops", "fill_holes",
          "fill_holes_patches"]

#: FillHoles uploads are recorded in messages of this size, so even the
#: small golden meshes take several slices of each kind.
UPLOAD_BYTES = 1024


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def polygon():
    """A noisy monkey-saddle rim of 80 vertices (3 decimals): edge
    protection inserts 19 vertices, the patch has 97 triangles."""
    n = 80
    rng = np.random.default_rng(5)
    t = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = 1 + rng.uniform(-0.3, 0.3, n)
    return np.round(np.c_[r * np.cos(t), r * np.sin(t),
                          np.cos(3 * t) + rng.uniform(-0.3, 0.3, n)], 3)


def pants():
    """Three rims (3 decimals): a wide one below two small ones side by
    side, the top ones running against it as a tube's rims do; joined by
    bridges first."""
    rng = np.random.default_rng(7)
    def ring(n, radius, z, x, turn):
        t = turn * 2 * np.pi * np.arange(n) / n
        return np.round(np.c_[x + radius * np.cos(t), radius * np.sin(t),
                              z + rng.uniform(-0.05, 0.05, n)], 3)
    return [ring(16, 1.0, 0.0, 0.0, 1), ring(10, 0.3, 1.0, -0.45, -1),
            ring(10, 0.3, 1.0, 0.45, -1)]


def sphere_with_hole():
    """A UV sphere (10 segments, 7 rings) with 24 triangles cut out."""
    seg, rings = 10, 7
    v = [(0.0, 0.0, 1.0)]
    for r in range(1, rings):
        theta = np.pi * r / rings
        for s in range(seg):
            phi = 2 * np.pi * s / seg
            v.append(tuple(round(float(x), 6) for x in (
                np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi),
                np.cos(theta))))
    v.append((0.0, 0.0, -1.0))
    ring = lambda r, s: 1 + (r - 1) * seg + s % seg  # noqa: E731
    faces = []
    for s in range(seg):
        faces.append((0, ring(1, s), ring(1, s + 1)))
    for r in range(1, rings - 1):
        for s in range(seg):
            a, b = ring(r, s), ring(r, s + 1)
            c, d = ring(r + 1, s + 1), ring(r + 1, s)
            if r in (2, 3, 4) and s in (1, 2, 3, 4):
                continue  # the hole
            faces += [(a, d, c), (a, c, b)]
    south = len(v) - 1
    for s in range(seg):
        faces.append((south, ring(rings - 1, s + 1), ring(rings - 1, s)))
    return np.array(v), np.array(faces)


def record(call, request):
    return [bytes(b) for b in call(request, timeout=30)]


def record_triangulate(channel, request):
    """The Triangulate response stream of `request`, as the server sent
    its bytes."""
    return record(channel.unary_stream(
        "/dot.v1.Triangulator/Triangulate",
        request_serializer=pb.TriangulateRequest.SerializeToString,
        response_deserializer=lambda b: b), request)


def read_obj(path):
    v, f = [], []
    for line in open(path):
        p = line.split()
        if p and p[0] == "v":
            v.append([float(x) for x in p[1:4]])
        elif p and p[0] == "f":
            f.append([int(x.split("/")[0]) - 1 for x in p[1:4]])
    return v, f


def read_off(path):
    tokens = [t for line in open(path) for t in line.split("#")[0].split()]
    assert tokens[0] == "OFF", tokens[:3]
    nv, nf = int(tokens[1]), int(tokens[2])
    at = 4
    v = []
    for _ in range(nv):
        v.append([float(x) for x in tokens[at:at + 3]])
        at += 3
    f = []
    for _ in range(nf):
        k = int(tokens[at])
        f.append([int(x) for x in tokens[at + 1:at + 1 + k]])
        at += 1 + k
    return v, f


def kinds(payloads, message_type):
    return [message_type.FromString(p).WhichOneof("payload") for p in payloads]


def write_off(path, vertices, faces):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(vertices)} {len(faces)} 0\n")
        for p in vertices:
            f.write(" ".join(repr(float(x)) for x in p) + "\n")
        for t in faces:
            f.write("3 " + " ".join(str(int(i)) for i in t) + "\n")


def record_fill(channel, request_id, options, vertices, faces):
    """The upload (FillHolesRequest messages, UPLOAD_BYTES each) and the
    response bytes of one FillHoles call."""
    requests = list(wire.fill_requests(request_id, options, vertices, faces,
                                       max_bytes=UPLOAD_BYTES))
    responses = [bytes(b) for b in channel.stream_stream(
        "/dot.v1.Triangulator/FillHoles",
        request_serializer=pb.FillHolesRequest.SerializeToString,
        response_deserializer=lambda b: b)(iter(requests), timeout=30)]
    return [r.SerializeToString() for r in requests], responses


def fill_local(dotctl, tmp, name, vertices, faces, flags):
    """dotctl fill-holes --local: (vertices, faces, report as JSON)."""
    off = os.path.join(tmp, name + ".off")
    write_off(off, vertices, faces)
    filled = os.path.join(tmp, name + ".filled.off")
    out = subprocess.run([dotctl, "fill-holes", "--local", off, "-o", filled,
                          "--json", *flags], check=True,
                         stdout=subprocess.PIPE, text=True).stdout
    fv, ff = read_off(filled)
    return fv, ff, json.loads(out)["report"]


def patches_of_whole_mesh(fv, ff, report, sent_vertices, sent_faces):
    """The patches answer, from dotctl's whole filled mesh and report (the
    layout of README "The result"; see the module's docstring)."""
    repair = report["repair"]
    assert not any(repair[k] for k in (
        "merged_vertices", "degenerate_faces", "duplicate_faces",
        "triangulated_polygons", "reoriented_faces")), \
        "the derivation needs a mesh the repair leaves as sent"
    assert report["input_vertices"] == sent_vertices
    assert report["input_faces"] == sent_faces
    filled = [h for h in report["holes"] if h["status"] == "HOLE_STATUS_FILLED"]
    split = [f for h in filled for f in h["split_faces"]]
    assert len(split) <= 1, "the derivation assigns appended pieces to one face"
    pieces = report["added_faces"] - sum(h["patch_triangles"] for h in filled)
    patches, vertex, face = [], sent_vertices, sent_faces + pieces
    for h in filled:
        count = h["boundary_inserted"] + h["refined_vertices"]
        patch = {"hole": h["id"], "first_vertex": vertex,
                 "vertices": fv[vertex:vertex + count],
                 "faces": ff[face:face + h["patch_triangles"]],
                 "replaced_faces": [
                     {"face": f, "triangles":
                      [ff[f]] + ff[sent_faces:sent_faces + pieces]}
                     for f in h["split_faces"]]}
        patches.append(patch)
        vertex += count
        face += h["patch_triangles"]
    assert vertex == len(fv) and face == len(ff), "the layout does not add up"
    return patches


def as_patches(doc_patches):
    return [dot_client.HolePatch(
        hole=p["hole"], first_vertex=p["first_vertex"],
        vertices=np.array(p["vertices"], dtype=np.float64).reshape(-1, 3),
        faces=np.array(p["faces"], dtype=np.int32).reshape(-1, 3),
        replaced_faces={r["face"]: np.array(r["triangles"], dtype=np.int32)
                        for r in p["replaced_faces"]})
        for p in doc_patches]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--server", default=os.path.join(ROOT, "build/server/dot-server"))
    ap.add_argument("--dotctl", default=os.path.join(ROOT, "build/client/dotctl"))
    ap.add_argument("--out", default=os.path.join(ROOT, "tests/golden"))
    ap.add_argument("--only", nargs="+", choices=GOLDEN, default=GOLDEN,
                    help="write only these recordings (a stream that did "
                    "not change keeps its committed bytes)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="dot-golden-")
    port = free_port()
    server = subprocess.Popen([args.server, "--listen", f"127.0.0.1:{port}",
                               "--metrics-port", "0", "--log-level", "warn",
                               "--threads", "2", "--chunk-kb", "1"])
    try:
        address = f"127.0.0.1:{port}"
        with dot_client.Client(address) as client:
            for _ in range(200):
                try:
                    client.health(timeout=1)
                    break
                except dot_client.DotError:
                    time.sleep(0.05)
        channel = grpc.insecure_channel(address)

        # Triangulate: the bytes as the server sent them.
        points = polygon()
        request = pb.TriangulateRequest(id="golden")
        request.polygon.coordinates.extend(points.reshape(-1).tolist())
        request.weights.squared_dihedral = 1
        request.options.search_space = pb.SEARCH_SPACE_DELAUNAY
        request.options.protect_edges = True
        request.options.omit_input_vertices = True
        request.options.progress_interval_ms = 1
        request.options.no_cache = True
        tri = record_triangulate(channel, request)
        xyz = os.path.join(tmp, "polygon.xyz")
        with open(xyz, "w") as f:
            for p in points:
                f.write(" ".join(repr(float(x)) for x in p) + "\n")
        obj = os.path.join(tmp, "expected.obj")
        subprocess.run([args.dotctl, "triangulate", "--local", xyz, "-o", obj,
                        "--space", "delaunay", "--protect-edges",
                        "--squared-dihedral", "1"], check=True)
        ev, et = read_obj(obj)
        summary = pb.TriangulateResponse.FromString(tri[-1]).summary
        tri_json = {
            "about": "tests/golden/triangulate.stream: the Triangulate "
                     "response stream of this request (scripts/"
                     "record_golden.py); expected: dotctl triangulate "
                     "--local on the same polygon",
            "rpc": "dot.v1.Triangulator/Triangulate",
            "request": {
                "id": "golden", "points": points.tolist(),
                "weights": {"squared_dihedral": 1.0},
                "options": {"search_space": "delaunay",
                            "protect_edges": True,
                            "omit_input_vertices": True,
                            "progress_interval_ms": 1, "no_cache": True}},
            "stream": kinds(tri, pb.TriangulateResponse),
            "expected": {
                "status": "ok",
                "vertices": ev, "triangles": et,
                "inserted_count": summary.inserted_count,
                "loop": list(summary.loop)}}

        # Triangulate with three loops: loop_sizes, loop and bridges.
        rims = pants()
        loop_points = np.concatenate(rims)
        request = pb.TriangulateRequest(id="golden-loops")
        request.polygon.coordinates.extend(loop_points.reshape(-1).tolist())
        request.polygon.loop_sizes.extend([len(r) for r in rims])
        request.weights.squared_dihedral = 1
        request.options.search_space = pb.SEARCH_SPACE_DELAUNAY
        request.options.omit_input_vertices = True
        request.options.progress_interval_ms = 1
        request.options.no_cache = True
        loops_tri = record_triangulate(channel, request)
        xyz = os.path.join(tmp, "pants.xyz")
        with open(xyz, "w") as f:
            f.write("\n\n".join("\n".join(" ".join(repr(float(x)) for x in p)
                                          for p in r) for r in rims) + "\n")
        obj = os.path.join(tmp, "pants.obj")
        subprocess.run([args.dotctl, "triangulate", "--local", xyz, "-o", obj,
                        "--space", "delaunay", "--squared-dihedral", "1"],
                       check=True)
        lv, lt = read_obj(obj)
        loops_summary = pb.TriangulateResponse.FromString(
            loops_tri[-1]).summary
        loops_json = {
            "about": "tests/golden/triangulate_loops.stream: the Triangulate "
                     "response stream of this request with three loops "
                     "(scripts/record_golden.py); expected: dotctl "
                     "triangulate --local on the same loops",
            "rpc": "dot.v1.Triangulator/Triangulate",
            "request": {
                "id": "golden-loops", "points": loop_points.tolist(),
                "loop_sizes": [len(r) for r in rims],
                "weights": {"squared_dihedral": 1.0},
                "options": {"search_space": "delaunay",
                            "omit_input_vertices": True,
                            "progress_interval_ms": 1, "no_cache": True}},
            "stream": kinds(loops_tri, pb.TriangulateResponse),
            "expected": {
                "status": "ok", "vertices": lv, "triangles": lt,
                "loop_sizes": list(loops_summary.loop_sizes),
                "loop": list(loops_summary.loop),
                "bridges": list(loops_summary.bridges)}}
        assert len(loops_summary.bridges) == 4, "two bridges"

        # FillHoles, the whole mesh back.
        vertices, faces = sphere_with_hole()
        options = pb.FillOptions(stage=pb.FILL_STAGE_FAIR)
        fill_up, fill = record_fill(channel, "golden-fill", options, vertices,
                                    faces)
        fv, ff, local_report = fill_local(args.dotctl, tmp, "sphere", vertices,
                                          faces, ["--stage", "fair"])
        report = pb.FillHolesResponse.FromString(fill[-1]).report
        fill_json = {
            "about": "tests/golden/fill_holes.stream: the FillHoles response "
                     "stream of this request (scripts/record_golden.py); "
                     "fill_holes.requests: its upload; expected: dotctl "
                     "fill-holes --local on the same mesh",
            "rpc": "dot.v1.Triangulator/FillHoles",
            "request": {"id": "golden-fill", "vertices": vertices.tolist(),
                        "faces": faces.tolist(),
                        "options": {"stage": "fair", "answer": "mesh"},
                        "upload_bytes": UPLOAD_BYTES},
            "stream": kinds(fill, pb.FillHolesResponse),
            "expected": {
                "vertices": fv, "faces": ff,
                "loops": report.loops, "filled": report.filled,
                "added_vertices": report.added_vertices,
                "added_faces": report.added_faces, "closed": report.closed}}
        assert local_report["filled"] == report.filled

        # FillHoles, the patches back.
        pv, pf = bumpy_grid_with_hole()
        patch_options = dot_client.FillOptions(
            stage="fair", skip_longest=True, density=4).to_proto("patches")
        patch_up, patched = record_fill(channel, "golden-patches",
                                        patch_options, pv, pf)
        wv, wf, whole_report = fill_local(
            args.dotctl, tmp, "bumpy", pv, pf,
            ["--stage", "fair", "--skip-longest", "--density", "4"])
        expected_patches = patches_of_whole_mesh(wv, wf, whole_report, len(pv),
                                                 len(pf))
        report = pb.FillHolesResponse.FromString(patched[-1]).report
        patches_json = {
            "about": "tests/golden/fill_holes_patches.stream: the FillHoles "
                     "response stream (answer FILL_ANSWER_PATCHES) of this "
                     "request (scripts/record_golden.py); "
                     "fill_holes_patches.requests: its upload; expected: the "
                     "patches derived from dotctl fill-holes --local's whole "
                     "mesh and report on the same mesh (whole_mesh)",
            "rpc": "dot.v1.Triangulator/FillHoles",
            "request": {"id": "golden-patches", "vertices": pv.tolist(),
                        "faces": pf.tolist(),
                        "options": {"stage": "fair", "skip_longest": True,
                                    "density": 4.0, "answer": "patches"},
                        "upload_bytes": UPLOAD_BYTES},
            "stream": kinds(patched, pb.FillHolesResponse),
            "expected": {
                "patches": expected_patches,
                "holes": [{"id": h["id"], "status": h["status"],
                           "escalation": h["escalation"],
                           "split_faces": h["split_faces"]}
                          for h in whole_report["holes"]],
                "loops": whole_report["loops"],
                "filled": whole_report["filled"],
                "skipped": whole_report["skipped"],
                "added_vertices": whole_report["added_vertices"],
                "added_faces": whole_report["added_faces"],
                "closed": whole_report["closed"],
                "whole_mesh": {"vertices": wv, "faces": wf}}}

        # The Python reassembly must agree before anything is written.
        got = wire.assemble_triangulate(
            [pb.TriangulateResponse.FromString(b) for b in tri], points)
        assert np.array_equal(got.vertices, np.array(ev)), "triangulate vertices"
        assert np.array_equal(got.triangles, np.array(et)), "triangulate triangles"
        got_fill = wire.assemble_fill(
            [pb.FillHolesResponse.FromString(b) for b in fill])
        assert np.array_equal(got_fill.vertices, np.array(fv)), "fill vertices"
        assert np.array_equal(got_fill.faces, np.array(ff)), "fill faces"
        got_patches = wire.assemble_patches(
            [pb.FillHolesResponse.FromString(b) for b in patched])
        want = as_patches(expected_patches)
        assert len(got_patches.patches) == len(want), "patch count"
        for got, exp in zip(got_patches.patches, want):
            assert (got.hole, got.first_vertex) == (exp.hole, exp.first_vertex)
            assert np.array_equal(got.vertices, exp.vertices), "patch vertices"
            assert np.array_equal(got.faces, exp.faces), "patch faces"
            assert got.replaced_faces.keys() == exp.replaced_faces.keys()
            for k in exp.replaced_faces:
                assert np.array_equal(got.replaced_faces[k],
                                      exp.replaced_faces[k]), "replaced"
        assert report.filled == whole_report["filled"]
        assert sum(1 for k in kinds(patched, pb.FillHolesResponse)
                   if k == "patch") >= 2, "the patch fits one message"

        got = wire.assemble_triangulate(
            [pb.TriangulateResponse.FromString(b) for b in loops_tri],
            loop_points)
        assert np.array_equal(got.vertices, np.array(lv)), "loops vertices"
        assert np.array_equal(got.triangles, np.array(lt)), "loops triangles"

        for name, payloads, doc in (("triangulate", tri, tri_json),
                                    ("triangulate_loops", loops_tri,
                                     loops_json),
                                    ("fill_holes", fill, fill_json),
                                    ("fill_holes_patches", patched,
                                     patches_json)):
            if name not in args.only:
                continue
            with open(os.path.join(args.out, name + ".stream"), "wb") as f:
                wire.write_length_prefixed(f, payloads)
            with open(os.path.join(args.out, name + ".json"), "w") as f:
                json.dump(doc, f, indent=None, separators=(",", ":"))
                f.write("\n")
            print(f"{name}: {len(payloads)} messages "
                  f"({', '.join(doc['stream'])})")
        for name, payloads in (("fill_holes", fill_up),
                               ("fill_holes_patches", patch_up)):
            if name not in args.only:
                continue
            with open(os.path.join(args.out, name + ".requests"), "wb") as f:
                wire.write_length_prefixed(f, payloads)
            print(f"{name}.requests: {len(payloads)} messages")
    finally:
        server.terminate()
        server.wait(timeout=30)


if __name__ == "__main__":
    main()
