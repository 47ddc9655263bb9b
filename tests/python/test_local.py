# SPDX-License-Identifier: AGPL-3.0-or-later
"""Local mode: dot_client.LocalServer and Client.local start a private
dot-server (Unix socket or loopback port), find it by argument,
$DOT_SERVER_PATH or PATH, stop it with the client, report a server that
cannot start, and never leave an orphan: a parent killed with SIGKILL
takes its server with it within seconds (and the directory it leaves is
swept by the next one)."""
import os
import signal
import subprocess
import sys
import tempfile
import time

import grpc
import numpy as np
import pytest

import dot_client
from conftest import server_path
from shapes import grid_with_hole


def gone(pid: int) -> bool:
    """Whether process `pid` has exited (a zombie nobody reaped counts:
    it runs no more)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] == "Z"
    except FileNotFoundError:
        return True


def wait_gone(pid: int, seconds: float) -> bool:
    deadline = time.monotonic() + seconds
    while not gone(pid):
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)
    return True


def test_client_local_starts_serves_and_stops_its_server():
    with dot_client.Client.local(server_path(), timeout=60) as client:
        server = client.server
        assert isinstance(server, dot_client.LocalServer)
        assert client.address == server.address
        assert server.address.startswith("unix:")
        socket_path = server.address[len("unix:"):]
        assert os.stat(os.path.dirname(socket_path)).st_mode & 0o077 == 0
        assert client.health() == "SERVING"
        v, f = grid_with_hole(10)
        assert client.fill_holes(v, f, skip_longest=True).report.filled == 1
        # Its own session: a Ctrl-C to this terminal's group misses it.
        assert os.getsid(server.pid) != os.getsid(0)
        pid = server.pid
    assert not server.running() and gone(pid)
    assert not os.path.exists(os.path.dirname(socket_path))
    with pytest.raises(dot_client.DotError) as e:
        client.health()
    assert e.value.code == grpc.StatusCode.FAILED_PRECONDITION


def test_tcp_transport_is_reachable_by_other_clients():
    with dot_client.LocalServer(server_path(), transport="tcp") as server:
        host, port = server.address.rsplit(":", 1)
        assert host == "127.0.0.1" and int(port) > 0
        with dot_client.Client(server.address) as other:
            assert other.health(timeout=10) == "SERVING"
        assert "LocalServer" in repr(server) and "running" in repr(server)
        pid = server.pid
    assert wait_gone(pid, 1)
    server.stop()  # idempotent
    assert "stopped" in repr(server)


def test_the_executable_is_found_by_argument_environment_then_path(
        monkeypatch, tmp_path):
    real = server_path()
    monkeypatch.delenv("DOT_SERVER_PATH", raising=False)
    monkeypatch.setenv("PATH", str(tmp_path))
    with pytest.raises(dot_client.DotError, match="'dot-server' is not on "
                       "PATH; pass executable= or set DOT_SERVER_PATH") as e:
        dot_client.find_server()
    assert e.value.code == grpc.StatusCode.UNAVAILABLE
    os.symlink(real, tmp_path / "dot-server")
    assert dot_client.find_server() == str(tmp_path / "dot-server")
    monkeypatch.setenv("DOT_SERVER_PATH", real)
    assert dot_client.find_server() == real
    assert dot_client.find_server(str(tmp_path / "dot-server")) == \
        str(tmp_path / "dot-server")
    with pytest.raises(dot_client.DotError, match="'no-such-server' is not "
                       "on PATH$"):
        dot_client.find_server("no-such-server")
    monkeypatch.setenv("DOT_SERVER_PATH", str(tmp_path / "missing"))
    with pytest.raises(dot_client.DotError, match=r"missing \(\$DOT_SERVER"
                       r"_PATH\) is not an executable file"):
        dot_client.Client.local()


def test_a_server_that_cannot_start_is_reported_and_left_nothing():
    before = set(os.listdir("/tmp"))
    with pytest.raises(dot_client.DotError) as e:
        dot_client.LocalServer(server_path(), args=["--no-such-flag"])
    assert e.value.code == grpc.StatusCode.UNAVAILABLE
    assert "exited with status" in e.value.message
    assert "no-such-flag" in e.value.message  # the log's end is quoted
    assert not {n for n in set(os.listdir("/tmp")) - before
                if n.startswith("dot-server-")}
    with pytest.raises(dot_client.InvalidInput, match="transport"):
        dot_client.LocalServer(server_path(), transport="pipe")


CHILD = """
import sys, time
import dot_client
server = dot_client.LocalServer(sys.argv[1])
print(server.pid, server.address, flush=True)
sys.stdin.readline()  # until the test has seen the server answer
if sys.argv[2] == "exit":
    sys.exit(0)  # no stop(): the interpreter's exit stops it
time.sleep(600)
"""


@pytest.mark.parametrize("how", ["SIGKILL", "exit"])
def test_the_server_dies_with_its_parent(how):
    """A Python process that started a local server ends without stopping
    it (killed with SIGKILL, which runs nothing; or exiting): the server
    must exit within a few seconds, not linger as an orphan."""
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD, server_path(), how],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
        env=dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path)))
    try:
        line = child.stdout.readline().split()
        assert line, "the child did not start a server"
        pid = int(line[0])
        assert not gone(pid)
        with dot_client.Client(line[1]) as c:
            assert c.health(timeout=10) == "SERVING"
        if how == "SIGKILL":
            child.send_signal(signal.SIGKILL)
        else:
            child.stdin.write("go\n")
            child.stdin.flush()
        child.wait(timeout=30)
        assert wait_gone(pid, 5), f"dot-server {pid} outlived its parent"
        # It removed its socket; its directory, if left, is empty.
        assert not os.path.exists(line[1][len("unix:"):])
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()


def test_empty_directories_of_killed_parents_are_swept(monkeypatch,
                                                       tmp_path):
    """A parent killed with SIGKILL leaves its server's (empty) directory;
    the next LocalServer removes such directories older than a minute,
    and none that is newer or holds something."""
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    old, new, full = (tmp_path / f"dot-server-{n}" for n in ("a", "b", "c"))
    for d in (old, new, full):
        d.mkdir(mode=0o700)
    (full / "dot.sock").write_text("")
    hour_ago = time.time() - 3600
    for d in (old, full):
        os.utime(d, (hour_ago, hour_ago))
    with dot_client.LocalServer(server_path()) as server:
        assert server.address.startswith(f"unix:{tmp_path}/dot-server-")
        assert not old.exists() and new.exists() and full.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "dot-server-b", "dot-server-c"]


def test_local_servers_are_independent():
    a = dot_client.Client.local(server_path())
    b = dot_client.Client.local(server_path())
    try:
        assert a.address != b.address
        assert a.health() == b.health() == "SERVING"
        a.close()
        assert not a.server.running() and b.server.running()
        r = b.triangulate(np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0),
                                    (0, 1, 0.0)]))
        assert r.triangles.shape == (2, 3)
    finally:
        a.close()
        b.close()
