#!/usr/bin/env python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""Writes the seed corpus of fill_stream_fuzz (tests/fuzz/corpus/
fill_stream_fuzz/): FillHolesRequest streams in the target's framing, a
2-byte little-endian length before each serialized message.

Usage: PYTHONPATH=build/client/python /usr/bin/python3 \\
           tests/fuzz/make_fill_seeds.py
"""
import pathlib
import struct

from dot_client._proto.dot.v1 import triangulation_pb2 as pb

OUT = (pathlib.Path(__file__).resolve().parent / "corpus" /
       "fill_stream_fuzz")


def grid(n, hole):
    """(n+1)^2 vertices, two triangles per quad, the quads in `hole` cut."""
    vertices = [c for i in range(n + 1) for j in range(n + 1)
                for c in (i, j, 0.1 * ((i * j) % 3))]
    faces = []
    for i in range(n):
        for j in range(n):
            if (i, j) in hole:
                continue
            a = i * (n + 1) + j
            faces += [a, a + 1, a + n + 2, a, a + n + 2, a + n + 1]
    return vertices, faces


def messages(options, vertices, faces, slices=1, face_sizes=None):
    """The upload in `slices` vertex slices and as many face slices."""
    out = []
    nv, nf = len(vertices) // 3, len(face_sizes or faces[::3])
    for k in range(slices):
        m = pb.FillHolesRequest()
        if k == 0:
            m.id = "seed"
            m.options.CopyFrom(options)
        lo, hi = nv * k // slices, nv * (k + 1) // slices
        m.mesh.first_vertex = lo
        m.mesh.vertices.extend(vertices[3 * lo:3 * hi])
        out.append(m)
    corner = 0
    for k in range(slices):
        m = pb.FillHolesRequest()
        lo, hi = nf * k // slices, nf * (k + 1) // slices
        m.mesh.first_vertex = nv
        m.mesh.first_triangle = lo
        if face_sizes:
            sizes = face_sizes[lo:hi]
            m.mesh.face_sizes.extend(sizes)
            m.mesh.triangles.extend(faces[corner:corner + sum(sizes)])
            corner += sum(sizes)
        else:
            m.mesh.triangles.extend(faces[3 * lo:3 * hi])
        out.append(m)
    return out


def write(name, stream):
    data = b""
    for m in stream:
        body = m if isinstance(m, bytes) else m.SerializeToString()
        data += struct.pack("<H", len(body)) + body
    (OUT / name).write_bytes(data)


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    for old in OUT.iterdir():
        old.unlink()
    fair = pb.FillOptions()
    v, f = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1], [0, 2, 1, 0, 1, 3, 1, 2, 3]
    write("tetrahedron_open", messages(fair, v, f))
    v, f = grid(6, {(2, 2), (2, 3), (3, 2)})
    write("grid_four_messages", messages(fair, v, f, slices=2))
    staged = pb.FillOptions(stage=pb.FILL_STAGE_TRIANGULATE, skip_longest=True,
                            answer=pb.FILL_ANSWER_PATCHES)
    staged.loops_through.append(2 * 7 + 2)
    write("triangulate_patches_loops_through", messages(staged, v, f))
    quads = [0, 1, 8, 7, 1, 2, 9, 8, 7, 8, 15, 14]
    write("polygons", messages(pb.FillOptions(no_repair=True), v[:3 * 16],
                               quads, face_sizes=[4, 4, 4]))
    stream = messages(fair, v, f, slices=2)
    stream.insert(2, b"\xff\xff\xff")  # does not parse: refused by position
    write("bad_middle", stream)
    # Channels: a colour per vertex, a UV per corner (a seam at i = 3),
    # polygons kept.
    for name, options in (("attributes_kept_polygons",
                           pb.FillOptions(keep_polygons=True,
                                          skip_longest=True)),
                          ("attributes_patches",
                           pb.FillOptions(answer=pb.FILL_ANSWER_PATCHES,
                                          skip_longest=True))):
        stream = messages(options, v, f)
        colour = pb.FillHolesRequest()
        colour.mesh.attribute.name, colour.mesh.attribute.dims = "color", 3
        for c in v[0::3]:
            colour.mesh.attribute.values.extend([0.5, c / 6, 0.25])
        uv = pb.FillHolesRequest()
        a = uv.mesh.attribute
        a.name, a.dims, a.per_corner = "uv", 2, True
        for k, corner in enumerate(f):
            x, y = v[3 * corner], v[3 * corner + 1]
            a.values.extend([x / 6 + (v[3 * f[k - k % 3]] >= 3), y / 6])
        a.indices.extend(range(len(f)))
        write(name, stream + [colour, uv])


if __name__ == "__main__":
    main()
