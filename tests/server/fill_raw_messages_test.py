#!/usr/bin/python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""FillHoles uploads that break off, stall or outlive a drain.

Raw bytes to a real dot-server on loopback (the mesh in MeshChunk slices,
field 6, as dot.v1 revision 2 has it), each case a rule of the upload or
a defect once seen:
- a revision 1 client (the mesh in fields 3-5) must be refused by name,
  INVALID_ARGUMENT saying "revision 2", and slices out of order named;
- a message that does not parse in the middle of the upload ended the
  upload as if the client had half-closed, and the partial mesh was filled
  and answered OK; it must be INVALID_ARGUMENT naming the message;
- a client that sends its mesh and never half-closes held a slot for as long
  as it liked (the deadline was checked only when a message arrived); the
  upload must end by a timer with DEADLINE_EXCEEDED;
- on SIGTERM the drain waited its whole period for such an idle uploader;
  the upload must end at once with UNAVAILABLE and the server exit;
- a client whose deadline passed before its first message was logged as
  cancelled and not counted; it must count as client_deadline.

Usage: fill_raw_messages_test.py PATH/TO/dot-server
"""
import signal
import sys
import threading
import time
import urllib.request

import grpc

import raw_wire
from raw_wire import doubles, field, free_port, mesh_chunk, varint


def first_message(request_id, time_budget_ms=0):
    """id, options and one triangle in one MeshChunk slice (field 6): a mesh
    with one hole."""
    options = field(10, 0, varint(time_budget_ms)) if time_budget_ms else b""
    mesh = mesh_chunk(0, (0, 0, 0, 1, 0, 0, 0, 1, 0), 0, (0, 1, 2))
    return (field(1, 2, request_id.encode()) + field(2, 2, options) +
            field(6, 2, mesh))


def revision_1_message(request_id):
    """The same upload as dot.v1 revision 1 sent it: vertices in field 3,
    faces in field 4 of FillHolesRequest itself."""
    return (field(1, 2, request_id.encode()) + field(2, 2, b"") +
            field(3, 2, doubles((0, 0, 0, 1, 0, 0, 0, 1, 0))) +
            field(4, 2, b"".join(varint(i) for i in (0, 1, 2))))


def start(server_path, *flags, metrics_port=0):
    server, channel = raw_wire.start_server(server_path, *flags,
                                            metrics_port=metrics_port)
    call = channel.stream_stream("/dot.v1.Triangulator/FillHoles",
                                 request_serializer=lambda b: b,
                                 response_deserializer=lambda b: b)
    return server, call


def stalled(messages, release):
    """The messages, then silence until `release` is set: no half-close."""
    yield from messages
    release.wait()


def expect_error(call, requests, code, words):
    try:
        responses = list(call(requests, timeout=60))
    except grpc.RpcError as e:
        assert e.code() == code, (e.code(), e.details())
        assert words in e.details(), e.details()
        return e
    raise AssertionError(f"expected {code}, got {len(responses)} responses")


def stopped_count(metrics_port, reason):
    text = urllib.request.urlopen(
        f"http://127.0.0.1:{metrics_port}/metrics", timeout=10).read().decode()
    for line in text.splitlines():
        if (line.startswith("dot_requests_stopped_total{") and
                'rpc="FillHoles"' in line and f'reason="{reason}"' in line):
            return float(line.split()[-1])
    return 0.0


def main():
    metrics_port = free_port()
    server, call = start(sys.argv[1], metrics_port=metrics_port)
    release = threading.Event()
    try:
        # A message that does not parse, after a good first one.
        expect_error(call, iter([first_message("bad"), b"\xff\xff\xff"]),
                     grpc.StatusCode.INVALID_ARGUMENT,
                     "message 1 of the upload does not parse")
        # A client of revision 1 (the mesh in fields 3-5) is told to update,
        # not answered as if it had sent an empty mesh.
        e = expect_error(call, iter([revision_1_message("old")]),
                         grpc.StatusCode.INVALID_ARGUMENT, "revision 2")
        assert "message 0 has fields this server does not know" in \
            e.details(), e.details()
        # Slices out of order are named.
        three = field(6, 2, mesh_chunk(0, (0, 0, 0, 1, 0, 0, 0, 1, 0)))
        expect_error(call, iter([field(1, 2, b"gap") + three,
                                 field(6, 2, mesh_chunk(5, (1, 1, 1)))]),
                     grpc.StatusCode.INVALID_ARGUMENT,
                     "message 1 starts at vertex 5 but 3 vertices have "
                     "arrived")
        expect_error(call, iter([first_message("faces"),
                                 field(6, 2, mesh_chunk(3, (), 0, (0, 2, 1)))]),
                     grpc.StatusCode.INVALID_ARGUMENT,
                     "message 1 starts at face 0 but 1 faces have arrived")
        # An upload that never half-closes ends by the request's budget.
        t0 = time.monotonic()
        expect_error(call, stalled([first_message("idle", 1500)], release),
                     grpc.StatusCode.DEADLINE_EXCEEDED,
                     "did not arrive within the time limit")
        print(f"idle upload with a 1.5 s budget ended after "
              f"{time.monotonic() - t0:.2f} s (client deadline 60 s)")
        # A client whose deadline passes before it sends anything.
        before = stopped_count(metrics_port, "client_deadline")
        try:
            list(call(stalled([], release), timeout=1))
            raise AssertionError("an empty upload was answered")
        except grpc.RpcError as e:
            assert e.code() == grpc.StatusCode.DEADLINE_EXCEEDED, e.code()
        time.sleep(0.5)  # the server's side of the call ends
        after = stopped_count(metrics_port, "client_deadline")
        assert after == before + 1, (before, after)
        # The server is still up and right.
        done = list(call(iter([first_message("after")]), timeout=60))
        assert done, "no answer after the bad uploads"
    finally:
        release.set()
        server.terminate()
        server.wait(timeout=30)

    # A drain ends an idle upload at once.
    server, call = start(sys.argv[1], "--drain-seconds", "60")
    release = threading.Event()
    outcome = {}

    def upload():
        try:
            list(call(stalled([first_message("draining")], release),
                      timeout=120))
            outcome["code"] = grpc.StatusCode.OK
        except grpc.RpcError as e:
            outcome["code"] = e.code()

    try:
        t = threading.Thread(target=upload)
        t.start()
        time.sleep(1)  # the first message is in
        t0 = time.monotonic()
        server.send_signal(signal.SIGTERM)
        server.wait(timeout=50)  # the drain period is 60 s
        took = time.monotonic() - t0
        t.join(timeout=30)
        assert outcome.get("code") == grpc.StatusCode.UNAVAILABLE, outcome
        print(f"SIGTERM with an idle upload: exited after {took:.2f} s "
              f"(drain period 60 s)")
    finally:
        release.set()
        if server.poll() is None:
            server.kill()
    print("PASS")


if __name__ == "__main__":
    main()
