#!/usr/bin/python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""Records the golden response streams of tests/golden/ (run once; commit).

Starts build/server/dot-server on a loopback port with 1 KiB mesh chunks
(--chunk-kb 1, so small meshes still come back in several chunks) and
records, byte for byte, the response stream of one Triangulate call (a
noisy 80-vertex saddle rim with edge protection, so the server inserts
vertices, and with omit_input_vertices, so the client must put the input
back) and of one FillHoles call (a small sphere with a hole, filled to the
fair stage). Each
stream is written as length-prefixed serialized messages (4-byte
little-endian length, then the bytes): triangulate.stream holds
dot.v1.TriangulateResponse messages, fill_holes.stream
dot.v1.FillHolesResponse messages.

The expected meshes beside them (triangulate.json, fill_holes.json) do not
come from any stream reassembly: they are what `dotctl ... --local`
computes in-process (the core library, no wire), written with 17
significant digits, so exact. The C++ test (tests/client/
golden_stream_test.cc) and the Python test (tests/python/test_golden.py)
replay the streams through their reassembly code and must get these meshes
exactly.

Usage: PYTHONPATH=build/client/python scripts/record_golden.py
       [--server build/server/dot-server] [--dotctl build/client/dotctl]
       [--out tests/golden]
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

import dot_client  # noqa: E402
from dot_client import wire  # noqa: E402
from dot_client._proto.dot.v1 import triangulation_pb2 as pb  # noqa: E402


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


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--server", default=os.path.join(ROOT, "build/server/dot-server"))
    ap.add_argument("--dotctl", default=os.path.join(ROOT, "build/client/dotctl"))
    ap.add_argument("--out", default=os.path.join(ROOT, "tests/golden"))
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
        raw = lambda b: b  # noqa: E731

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
        tri = record(channel.unary_stream(
            "/dot.v1.Triangulator/Triangulate",
            request_serializer=pb.TriangulateRequest.SerializeToString,
            response_deserializer=raw), request)
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

        # FillHoles: options first, the mesh in one more message.
        vertices, faces = sphere_with_hole()
        options = pb.FillOptions(stage=pb.FILL_STAGE_FAIR)
        requests = list(wire.fill_requests("golden-fill", options, vertices,
                                           faces))
        fill = [bytes(b) for b in channel.stream_stream(
            "/dot.v1.Triangulator/FillHoles",
            request_serializer=pb.FillHolesRequest.SerializeToString,
            response_deserializer=raw)(iter(requests), timeout=30)]
        off = os.path.join(tmp, "mesh.off")
        with open(off, "w") as f:
            f.write(f"OFF\n{len(vertices)} {len(faces)} 0\n")
            for p in vertices:
                f.write(" ".join(repr(float(x)) for x in p) + "\n")
            for t in faces:
                f.write("3 " + " ".join(str(int(i)) for i in t) + "\n")
        filled = os.path.join(tmp, "filled.off")
        subprocess.run([args.dotctl, "fill-holes", "--local", off, "-o",
                        filled, "--stage", "fair", "-q"], check=True)
        fv, ff = read_off(filled)
        report = pb.FillHolesResponse.FromString(fill[-1]).report
        fill_json = {
            "about": "tests/golden/fill_holes.stream: the FillHoles response "
                     "stream of this request (scripts/record_golden.py); "
                     "expected: dotctl fill-holes --local on the same mesh",
            "rpc": "dot.v1.Triangulator/FillHoles",
            "request": {"id": "golden-fill", "vertices": vertices.tolist(),
                        "faces": faces.tolist(),
                        "options": {"stage": "fair"}},
            "stream": kinds(fill, pb.FillHolesResponse),
            "expected": {
                "vertices": fv, "faces": ff,
                "loops": report.loops, "filled": report.filled,
                "added_vertices": report.added_vertices,
                "added_faces": report.added_faces, "closed": report.closed}}

        # The Python reassembly must agree before anything is written.
        got = wire.assemble_triangulate(
            [pb.TriangulateResponse.FromString(b) for b in tri], points)
        assert np.array_equal(got.vertices, np.array(ev)), "triangulate vertices"
        assert np.array_equal(got.triangles, np.array(et)), "triangulate triangles"
        got_fill = wire.assemble_fill(
            [pb.FillHolesResponse.FromString(b) for b in fill])
        assert np.array_equal(got_fill.vertices, np.array(fv)), "fill vertices"
        assert np.array_equal(got_fill.faces, np.array(ff)), "fill faces"

        for name, payloads, doc in (("triangulate", tri, tri_json),
                                    ("fill_holes", fill, fill_json)):
            with open(os.path.join(args.out, name + ".stream"), "wb") as f:
                wire.write_length_prefixed(f, payloads)
            with open(os.path.join(args.out, name + ".json"), "w") as f:
                json.dump(doc, f, indent=None, separators=(",", ":"))
                f.write("\n")
            print(f"{name}: {len(payloads)} messages "
                  f"({', '.join(doc['stream'])})")
    finally:
        server.terminate()
        server.wait(timeout=30)


if __name__ == "__main__":
    main()
