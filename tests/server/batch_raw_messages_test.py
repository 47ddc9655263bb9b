#!/usr/bin/python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""A TriangulateBatch message that does not parse fails alone.

gRPC reports such a message to a C++ reactor as the end of the stream, so
the server once ended the batch with OK and dropped the items after it. This
test speaks raw bytes to a real dot-server on loopback: a truncated message,
then a valid polygon; the first must get an INVALID_ARGUMENT Error naming its
place in the stream, the second its mesh and summary, the stream OK.

Usage: batch_raw_messages_test.py PATH/TO/dot-server
"""
import struct
import sys

from raw_wire import field, start_server


def request(request_id, points):
    coordinates = b"".join(struct.pack("<d", c) for p in points for c in p)
    polygon = field(1, 2, coordinates)  # Polygon.coordinates, packed
    return field(1, 2, request_id.encode()) + field(2, 2, polygon)


def main():
    server, channel = start_server(sys.argv[1])
    try:
        call = channel.stream_stream(
            "/dot.v1.Triangulator/TriangulateBatch",
            request_serializer=lambda b: b,
            response_deserializer=lambda b: b)
        truncated = b"\x0a\x64ab"  # an id of 100 bytes with 2 present
        good = request("ok", [(0, 0, 0), (1, 0, 0), (1, 1, 0.3), (0, 1, 0)])
        responses = list(call(iter([truncated, good]), timeout=30))
        errors = [r for r in responses if b"does not parse" in r]
        assert len(errors) == 1, responses
        assert b"message 1 of this stream" in errors[0], errors[0]
        # TriangulateResponse.id = "ok" and a Summary (field 4).
        ok = [r for r in responses if r.startswith(field(1, 2, b"ok"))]
        assert any(r[4:5] == b"\x22" for r in ok), responses
        print(f"PASS: {len(responses)} responses, the bad message failed alone")
    finally:
        server.terminate()
        server.wait(timeout=30)


if __name__ == "__main__":
    main()
