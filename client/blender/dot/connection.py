# SPDX-License-Identifier: AGPL-3.0-or-later
"""The add-on's server: the one in the preferences, or a dot-server this
add-on starts on a loopback port ("run locally") and stops with Blender.
Starting and stopping it is dot_client.LocalServer's, the one
implementation the Python client's local mode uses too."""
import atexit
import os
import threading

import grpc

try:  # the copy vendored into the add-on zip by the build
    from .vendor import dot_client
except ImportError:  # running from client/blender with dot_client on sys.path
    import dot_client

_lock = threading.Lock()
_clients = {}
_local = {"server": None, "executable": None}


def local_server(executable="dot-server", wait_s=30.0):
    """The address of the dot-server this add-on runs on 127.0.0.1, started
    on first use: ``executable`` is a path or a name on PATH; the default
    name (or "") means $DOT_SERVER_PATH when set, else dot-server on PATH.

    It is a dot_client.LocalServer: started with --exit-with-stdin on a
    pipe only Blender holds, so however Blender ends (killed, it runs no
    atexit hook) the server reads end-of-file and exits instead of
    listening on."""
    with _lock:
        s = _local["server"]
        if s is not None and s.running() and \
                _local["executable"] == executable:
            return s.address
        _stop_locked()
        try:
            s = dot_client.LocalServer(
                None if executable in ("", "dot-server") else executable,
                transport="tcp", log_level="warn", wait_s=wait_s)
        except dot_client.DotError as e:
            raise dot_client.DotError(
                grpc.StatusCode.UNAVAILABLE,
                f"no DOT server is set and {e.message}: set a server in "
                "the add-on's preferences or install dot-server") from None
        _local.update(server=s, executable=executable)
        return s.address


def _stop_locked():
    s = _local["server"]
    _local.update(server=None, executable=None)
    if s is not None:
        s.stop()


def stop_local_server():
    """Stops the local dot-server, if this add-on started one."""
    with _lock:
        _stop_locked()


def local_server_running():
    s = _local["server"]
    return s is not None and s.running()


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
