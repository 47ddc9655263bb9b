#!/usr/bin/python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""A request that does not parse is refused by name, in every RPC.

With typed methods, gRPC's C++ callback API answered such a request to
Triangulate, GetServerInfo or GetSource with UNIMPLEMENTED and no message,
as if the method did not exist. This test sends raw bytes to a real
dot-server on loopback: ff ff ff (a truncated varint) must get
INVALID_ARGUMENT naming the RPC and the message type, and the server must
then still answer a good request.

Usage: request_raw_messages_test.py PATH/TO/dot-server
"""
import sys

import grpc

from raw_wire import start_server

BAD = b"\xff\xff\xff"


def main():
    server, channel = start_server(sys.argv[1])
    try:
        raw = {"request_serializer": lambda b: b,
               "response_deserializer": lambda b: b}
        cases = [
            ("Triangulate", "TriangulateRequest",
             lambda m: list(channel.unary_stream(m, **raw)(BAD, timeout=30))),
            ("GetServerInfo", "GetServerInfoRequest",
             lambda m: channel.unary_unary(m, **raw)(BAD, timeout=30)),
            ("GetSource", "GetSourceRequest",
             lambda m: list(channel.unary_stream(m, **raw)(BAD, timeout=30))),
        ]
        for rpc, message, call in cases:
            try:
                call(f"/dot.v1.Triangulator/{rpc}")
                raise AssertionError(f"{rpc}: a request that does not parse "
                                     "was answered")
            except grpc.RpcError as e:
                assert e.code() == grpc.StatusCode.INVALID_ARGUMENT, \
                    (rpc, e.code(), e.details())
                assert f"dot.v1.{message}" in e.details(), (rpc, e.details())
                print(f"{rpc}: {e.code().name}: {e.details()}")
        # Still up: an empty GetServerInfoRequest is a valid one.
        info = channel.unary_unary("/dot.v1.Triangulator/GetServerInfo",
                                   **raw)(b"", timeout=30)
        assert b"AGPL-3.0-or-later" in info, info[:200]
        print("PASS")
    finally:
        server.terminate()
        server.wait(timeout=30)


if __name__ == "__main__":
    main()
