# SPDX-License-Identifier: AGPL-3.0-or-later
"""dot_client.LocalServer: a private dot-server child process that lives
no longer than the Python process that started it.

The one implementation of "run a server locally": :meth:`Client.local`
uses it, and so does the Blender add-on's Run Locally.
"""
from __future__ import annotations

import os
import shutil
import socket
import stat
import subprocess
import tempfile
import threading
import time
import weakref
from typing import IO, Any, List, Optional, Sequence

import grpc

from . import _validate as check
from ._errors import DotError, InvalidInput

SERVER_NAME = "dot-server"
ENV_PATH = "DOT_SERVER_PATH"
_TRANSPORTS = ("unix", "tcp")
# sun_path holds 108 bytes; gRPC wants the path and its NUL in it.
_UNIX_PATH_MAX = 100


def find_server(executable: Optional[str] = None) -> str:
    """The dot-server to run: ``executable`` when given (a path, or a name
    looked up on PATH), else the ``DOT_SERVER_PATH`` environment variable
    (the same), else ``dot-server`` on PATH. Returns an absolute path;
    raises :class:`DotError` (``UNAVAILABLE``) naming what was tried when
    none is an executable file."""
    if executable is not None and not isinstance(executable, str):
        raise InvalidInput(f"executable must be a path or a program name; "
                           f"got {executable!r}")
    if executable:
        name, source = executable, "executable"
    elif os.environ.get(ENV_PATH):
        name, source = os.environ[ENV_PATH], f"${ENV_PATH}"
    else:
        name, source = SERVER_NAME, ""
    if os.path.sep in name:
        path = os.path.abspath(os.path.expanduser(name))
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
        where = f" ({source})" if source else ""
        raise DotError(grpc.StatusCode.UNAVAILABLE,
                       f"{path}{where} is not an executable file")
    found = shutil.which(name)
    if found is None:
        hint = ("" if source else f"; pass executable= or set {ENV_PATH}")
        raise DotError(grpc.StatusCode.UNAVAILABLE,
                       f"{name!r} is not on PATH{hint}")
    return os.path.abspath(found)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port: int = s.getsockname()[1]
        return port


def _accepts(address: str) -> bool:
    """Whether the listening socket of ``address`` (``unix:PATH`` or
    ``127.0.0.1:PORT``) accepts a connection now. Polled before the first
    gRPC call: a channel that found nothing listening waits out gRPC's
    reconnect backoff (a second) before it tries again."""
    try:
        if address.startswith("unix:"):
            with socket.socket(socket.AF_UNIX) as s:
                s.connect(address[len("unix:"):])
        else:
            host, port = address.rsplit(":", 1)
            with socket.create_connection((host, int(port)), timeout=1):
                pass
        return True
    except OSError:
        return False


def _sweep(parent: str, older_than_s: float = 60.0) -> None:
    """Removes the empty ``dot-server-*`` directories of this user in
    ``parent`` older than a minute: those of servers whose parent was
    killed (the server removes its socket as it exits, nobody removes the
    directory). A running server's directory holds its socket, so rmdir
    leaves it; a directory made in the last minute may be a server still
    starting, and is left too."""
    now = time.time()
    try:
        names = [n for n in os.listdir(parent) if n.startswith("dot-server-")]
    except OSError:
        return
    for name in names:
        path = os.path.join(parent, name)
        try:
            st = os.lstat(path)
            if st.st_uid == os.getuid() and stat.S_ISDIR(st.st_mode) and \
                    now - st.st_mtime > older_than_s:
                os.rmdir(path)  # only if empty
        except OSError:
            pass


def _stop(process: "subprocess.Popen[bytes]", owner: int, directory: str,
          log: IO[bytes], timeout: float) -> None:
    """Ends the server (the finalizer of a LocalServer): its stdin closed,
    it drains and exits; SIGTERM, then SIGKILL, if it does not."""
    if os.getpid() != owner:
        # A forked child's copy: leave the parent's server alone, and drop
        # this copy of the pipe so the server does not wait for this child.
        try:
            if process.stdin is not None:
                process.stdin.close()
        except OSError:
            pass
        return
    try:
        if process.stdin is not None:
            try:
                process.stdin.close()
            except OSError:
                pass
        try:
            process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            process.terminate()
            try:
                process.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
    finally:
        log.close()
        if directory:
            shutil.rmtree(directory, ignore_errors=True)


class LocalServer:
    """A private dot-server, started on a Unix socket in a private
    directory (``transport="unix"``, the default: only this user can
    connect, no port to race for) or on a free 127.0.0.1 port
    (``transport="tcp"``: other programs on this machine, ``dotctl``
    among them, can use ``address``), and stopped with the Python process
    that started it however that process ends.

    ``executable``: the dot-server to run (a path or a name on PATH);
    None: ``$DOT_SERVER_PATH``, else ``dot-server`` on PATH (see
    :func:`find_server`). ``threads``: its compute threads (0: one per
    core). ``log_level``: the server's (``"warn"``: only trouble); its log
    goes to a private temporary file, whose end is quoted when the server
    fails to start (:meth:`log` reads it). ``args``: more ``dot-server``
    flags (``["--cache-mb", "0"]``). ``wait_s``: how long to wait for it
    to answer health checks.

    When the constructor returns, the server answers ``SERVING`` on
    ``address`` (a gRPC target: ``unix:/tmp/dot-server-.../dot.sock`` or
    ``127.0.0.1:PORT``); otherwise it raised :class:`DotError`
    (``UNAVAILABLE``: no executable, it exited, or it did not answer in
    ``wait_s``) and left nothing running.

    **Never an orphan.** The server runs with ``--exit-with-stdin`` and its
    stdin is a pipe whose only write end this process holds: when this
    process ends in any way (``sys.exit``, an exception, ``SIGKILL``, a
    crash, a Jupyter kernel restarted), the operating system closes that
    end, the server reads end-of-file, drains and exits. No signal of the
    parent (PR_SET_PDEATHSIG) or polling is needed, and it works from
    threads (Blender's). The write end is not inherited by programs this
    process runs (``subprocess`` closes it); a child made by ``os.fork``
    without ``exec`` (``multiprocessing``'s "fork" workers) holds a copy
    until it ends, so the server then outlives the parent until the last
    such child is gone. The server runs in its own session, so a Ctrl-C in
    the terminal (or a notebook's "interrupt") stops the call, not the
    server.

    :meth:`stop` (also on ``with`` exit, on garbage collection and at
    interpreter exit) closes the pipe, waits for the server to exit
    (SIGTERM, then SIGKILL after ``stop_timeout`` seconds each) and
    removes its directory. (After a SIGKILL nothing runs to remove it:
    the server removes its socket as it exits, and the next LocalServer
    removes such empty directories.) Use as a context manager::

        with dot_client.LocalServer() as server:
            with dot_client.Client(server.address) as client:
                ...

    or let :meth:`Client.local` own one.
    """

    def __init__(self, executable: Optional[str] = None, *,
                 transport: str = "unix", threads: int = 0,
                 log_level: str = "warn", args: Sequence[str] = (),
                 wait_s: float = 30.0, stop_timeout: float = 10.0) -> None:
        self.executable = find_server(executable)
        self.transport = check.choice("transport", transport, _TRANSPORTS)
        threads = check.integer("threads", threads, minimum=0)
        wait_s = check.number("wait_s", wait_s, minimum=0)
        self.stop_timeout = check.number("stop_timeout", stop_timeout,
                                         minimum=0)
        if isinstance(args, str) or not all(isinstance(a, str) for a in args):
            raise InvalidInput("args must be a list of strings (dot-server "
                               "flags)")
        self.address = ""
        self.process: Optional["subprocess.Popen[bytes]"] = None
        self._lock = threading.Lock()
        self._finalizer: Optional[weakref.finalize] = None
        self._log: Optional[IO[bytes]] = None
        # A port taken between our probe and the server's bind is tried
        # again with another one.
        attempts = 3 if self.transport == "tcp" else 1
        for attempt in range(attempts):
            self._start(threads, log_level, list(args))
            try:
                self._wait(wait_s)
                return
            except DotError:
                exited = self.process is not None and \
                    self.process.poll() is not None
                text = self.log()
                self.stop()
                if attempt + 1 < attempts and exited and \
                        "cannot listen" in text:
                    continue
                raise
            except BaseException:  # KeyboardInterrupt while waiting
                self.stop()
                raise

    def _start(self, threads: int, log_level: str, args: List[str]) -> None:
        directory = ""
        if self.transport == "unix":
            _sweep(tempfile.gettempdir())
            directory = tempfile.mkdtemp(prefix="dot-server-")
            path = os.path.join(directory, "dot.sock")
            if len(path) > _UNIX_PATH_MAX:  # a long $TMPDIR
                shutil.rmtree(directory, ignore_errors=True)
                directory = tempfile.mkdtemp(prefix="dot-server-", dir="/tmp")
                path = os.path.join(directory, "dot.sock")
            self.address = f"unix:{path}"
        else:
            self.address = f"127.0.0.1:{_free_port()}"
        log = tempfile.TemporaryFile(prefix="dot-server-", suffix=".log")
        command = [self.executable, "--listen", self.address,
                   "--metrics-port", "0", "--log-level", log_level,
                   "--drain-seconds", "1", "--threads", str(threads),
                   "--exit-with-stdin", *args]
        try:
            # stdin: a pipe whose only write end is ours (see the class
            # docstring). Its own session: a Ctrl-C meant for the caller
            # does not reach it.
            process = subprocess.Popen(command, stdin=subprocess.PIPE,
                                       stdout=log, stderr=subprocess.STDOUT,
                                       close_fds=True, start_new_session=True)
        except OSError as e:
            log.close()
            if directory:
                shutil.rmtree(directory, ignore_errors=True)
            raise DotError(grpc.StatusCode.UNAVAILABLE,
                           f"cannot run {self.executable}: {e.strerror}"
                           ) from None
        self.process = process
        self._log = log
        self._finalizer = weakref.finalize(self, _stop, process, os.getpid(),
                                           directory, log, self.stop_timeout)

    def _wait(self, wait_s: float) -> None:
        from ._client import Client  # _client imports this module

        process = self.process
        assert process is not None
        deadline = time.monotonic() + wait_s
        client: Optional[Client] = None
        try:
            while True:
                if process.poll() is not None:
                    raise DotError(
                        grpc.StatusCode.UNAVAILABLE,
                        f"the local dot-server ({self.executable}) exited "
                        f"with status {process.returncode}"
                        f"{self._log_tail()}")
                if client is None and _accepts(self.address):
                    client = Client(self.address)
                if client is not None:
                    try:
                        if client.health(timeout=1) == "SERVING":
                            return
                    except DotError:
                        pass
                if time.monotonic() > deadline:
                    raise DotError(
                        grpc.StatusCode.UNAVAILABLE,
                        f"the local dot-server ({self.executable}) did not "
                        f"answer in {wait_s:g} s{self._log_tail()}")
                time.sleep(0.01 if client is None else 0.05)
        finally:
            if client is not None:
                client.close()

    def log(self) -> str:
        """The server's log so far (empty once stopped)."""
        log = self._log
        if log is None or log.closed:
            return ""
        # pread: the server shares the file's offset; reading must not
        # move it.
        fd = log.fileno()
        return os.pread(fd, os.fstat(fd).st_size, 0).decode(errors="replace")

    def _log_tail(self, lines: int = 5) -> str:
        text = self.log().strip().splitlines()[-lines:]
        return (": " + " / ".join(text)) if text else ""

    @property
    def pid(self) -> Optional[int]:
        """The server's process id (None before it was started)."""
        return None if self.process is None else self.process.pid

    def running(self) -> bool:
        """Whether the server process is still running."""
        return self.process is not None and self.process.poll() is None

    def stop(self) -> None:
        """Stops the server and waits for it to exit (idempotent; see the
        class docstring)."""
        with self._lock:
            if self._finalizer is not None:
                self._finalizer()

    def __enter__(self) -> "LocalServer":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.stop()

    def __repr__(self) -> str:
        state = "running" if self.running() else "stopped"
        return (f"dot_client.LocalServer({self.address!r}, pid {self.pid}, "
                f"{state})")
