# SPDX-License-Identifier: AGPL-3.0-or-later
"""The add-on's server: the one in the preferences, or a dot-server this
add-on starts on a loopback port ("run locally") and stops with Blender."""
import atexit
import os
import shutil
import socket
import subprocess
import threading
import time

import grpc

try:  # the copy vendored into the add-on zip by the build
    from .vendor import dot_client
except ImportError:  # running from client/blender with dot_client on sys.path
    import dot_client

_lock = threading.Lock()
_clients = {}
_local = {"process": None, "address": None, "executable": None}


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _find_executable(name):
    if os.path.sep in name:
        path = os.path.abspath(os.path.expanduser(name))
        return path if os.access(path, os.X_OK) else None
    return shutil.which(name)


def local_server(executable="dot-server", wait_s=30.0):
    """The address of the dot-server this add-on runs on 127.0.0.1, started
    (from PATH, or the given path) on first use."""
    with _lock:
        p = _local["process"]
        if p is not None and p.poll() is None and \
                _local["executable"] == executable:
            return _local["address"]
        _stop_locked()
        path = _find_executable(executable)
        if path is None:
            raise dot_client.DotError(
                grpc.StatusCode.UNAVAILABLE,
                f"no DOT server is set and {executable!r} is "
                "not on PATH: set a server in the add-on's preferences or "
                "install dot-server")
        address = f"127.0.0.1:{_free_port()}"
        process = subprocess.Popen(
            [path, "--listen", address, "--metrics-port", "0",
             "--log-level", "warn", "--drain-seconds", "1",
             "--exit-with-stdin"],
            # Blender holds the pipe's only write end: however Blender
            # ends (killed, it runs no atexit hook), the server reads EOF
            # and exits instead of listening on.
            stdin=subprocess.PIPE, stdout=subprocess.DEVNULL)
        _local.update(process=process, address=address, executable=executable)
    with dot_client.Client(address) as c:
        deadline = time.monotonic() + wait_s
        while True:
            if process.poll() is not None:
                raise dot_client.DotError(
                    grpc.StatusCode.UNAVAILABLE,
                    f"the local dot-server ({path}) exited "
                    f"with status {process.returncode}")
            try:
                if c.health(timeout=1) == "SERVING":
                    return address
            except dot_client.DotError:
                pass
            if time.monotonic() > deadline:
                stop_local_server()
                raise dot_client.DotError(
                    grpc.StatusCode.UNAVAILABLE,
                    f"the local dot-server did not start in "
                    f"{wait_s:.0f} s")
            time.sleep(0.05)


def _stop_locked():
    p = _local["process"]
    _local.update(process=None, address=None, executable=None)
    if p is not None and p.poll() is None:
        p.terminate()
        try:
            p.wait(timeout=10)
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait()


def stop_local_server():
    """Stops the local dot-server, if this add-on started one."""
    with _lock:
        _stop_locked()


def local_server_running():
    p = _local["process"]
    return p is not None and p.poll() is None


atexit.register(stop_local_server)


def client(prefs):
    """A dot_client.Client for the add-on preferences `prefs`."""
    address = prefs.server_address.strip()
    if not address:
        if not prefs.run_locally:
            raise dot_client.DotError(
                grpc.StatusCode.FAILED_PRECONDITION,
                "no DOT server is set: enter one in the add-on's preferences "
                "(Edit > Preferences > Add-ons > DOT) or enable Run Locally")
        address = local_server(prefs.server_executable.strip() or "dot-server")
    tls = tuple(bpy_path(p) for p in (prefs.tls_ca, prefs.tls_cert,
                                      prefs.tls_key))
    key = (address,) + tls + (prefs.timeout,)
    with _lock:
        c = _clients.get(key)
        if c is None:
            ca, cert, tkey = tls
            c = dot_client.Client(address, tls_ca=ca, tls_cert=cert,
                                  tls_key=tkey, timeout=prefs.timeout)
            _clients[key] = c
        return c


def bpy_path(path):
    """A preferences file path as an absolute path, or None when empty."""
    if not path:
        return None
    try:
        import bpy
        path = bpy.path.abspath(path)
    except ImportError:  # pragma: no cover
        pass
    return os.path.abspath(os.path.expanduser(path))


def close_all():
    """Closes every client and stops the local server (unregister)."""
    with _lock:
        for c in _clients.values():
            c.close()
        _clients.clear()
    stop_local_server()
