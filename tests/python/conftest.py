# SPDX-License-Identifier: AGPL-3.0-or-later
"""Fixtures: real dot-server processes on loopback ports, and clients.

ctest runs these tests with PYTHONPATH at the build's dot_client
(build/client/python) and DOT_SERVER_PATH naming the dot-server binary;
run by hand:

    PYTHONPATH=build/client/python DOT_SERVER_PATH=build/server/dot-server \\
        /usr/bin/python3 -m pytest tests/python
"""
import os
import socket
import subprocess
import time
from typing import Iterator

import pytest

import dot_client

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def server_path() -> str:
    path = os.environ.get("DOT_SERVER_PATH",
                          os.path.join(ROOT, "build", "server", "dot-server"))
    if not os.access(path, os.X_OK):
        pytest.fail(f"no dot-server at {path} (set DOT_SERVER_PATH)")
    return path


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Server:
    """A dot-server child process listening on 127.0.0.1."""

    def __init__(self, *flags: str, tls_ca: str = None, tls_cert: str = None,
                 tls_key: str = None) -> None:
        self.port = free_port()
        self.address = f"127.0.0.1:{self.port}"
        self.process = subprocess.Popen(
            [server_path(), "--listen", self.address, "--metrics-port", "0",
             "--log-level", "error", "--drain-seconds", "1",
             "--threads", "2", *flags],
            stdout=subprocess.DEVNULL)
        # Ready when its health check answers (at most 30 s).
        with dot_client.Client(self.address, tls_ca=tls_ca, tls_cert=tls_cert,
                               tls_key=tls_key) as c:
            deadline = time.monotonic() + 30
            while True:
                if self.process.poll() is not None:
                    raise RuntimeError(f"dot-server exited with "
                                       f"{self.process.returncode}")
                try:
                    if c.health(timeout=1) == "SERVING":
                        return
                except dot_client.DotError:
                    pass
                if time.monotonic() > deadline:
                    self.stop()
                    raise RuntimeError("dot-server did not start in 30 s")
                time.sleep(0.05)

    def alive(self) -> bool:
        return self.process.poll() is None

    def stop(self) -> None:
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()


@pytest.fixture(scope="session")
def server() -> Iterator[Server]:
    s = Server()
    yield s
    s.stop()


@pytest.fixture(scope="session")
def limited_server() -> Iterator[Server]:
    """Small limits, for RESOURCE_EXHAUSTED."""
    s = Server("--max-vertices", "100", "--fill-max-faces", "1000",
               "--fill-max-vertices", "1000")
    yield s
    s.stop()


@pytest.fixture
def client(server: Server) -> Iterator[dot_client.Client]:
    with dot_client.Client(server.address, timeout=60) as c:
        yield c
