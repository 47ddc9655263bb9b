# SPDX-License-Identifier: AGPL-3.0-or-later
"""Protobuf wire bytes by hand, and a free loopback port: what the raw
message tests (batch_raw_messages_test.py, fill_raw_messages_test.py) need
to send messages that do not parse, or that use fields a server no longer
knows."""
import socket
import struct


def varint(n):
    out = b""
    while True:
        b = n & 0x7F
        n >>= 7
        out += bytes([b | (0x80 if n else 0)])
        if not n:
            return out


def field(number, wire_type, payload):
    key = varint(number << 3 | wire_type)
    if wire_type == 2:
        return key + varint(len(payload)) + payload
    return key + payload


def doubles(values):
    """Packed doubles (a repeated double field's payload)."""
    return b"".join(struct.pack("<d", v) for v in values)


def mesh_chunk(first_vertex=0, vertices=(), first_triangle=0, triangles=()):
    """dot.v1.MeshChunk bytes: first_vertex 1, vertices 2 (packed doubles),
    first_triangle 3, triangles 4 (packed varints); zeros left out, as
    protobuf leaves them out."""
    out = field(1, 0, varint(first_vertex)) if first_vertex else b""
    if vertices:
        out += field(2, 2, doubles(vertices))
    if first_triangle:
        out += field(3, 0, varint(first_triangle))
    if triangles:
        out += field(4, 2, b"".join(varint(i) for i in triangles))
    return out


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(server_path, *flags, metrics_port=0):
    """A dot-server on a free loopback port (metrics on `metrics_port`, off
    by default) and a ready channel to it."""
    import subprocess

    import grpc
    port = free_port()
    server = subprocess.Popen([server_path, "--listen", f"127.0.0.1:{port}",
                               "--metrics-port", str(metrics_port),
                               "--log-level", "warn", *flags])
    channel = grpc.insecure_channel(f"127.0.0.1:{port}")
    grpc.channel_ready_future(channel).result(timeout=20)
    return server, channel
