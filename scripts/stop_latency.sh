#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# How long dot-server keeps computing after a FillHoles client gives up:
# starts dot-server (metrics on), makes a bumpy torus with holes (closed mesh
# from Python, holes cut by `dotctl generate holes`), then for each case
# runs `dotctl fill-holes --timeout T` (the client's deadline passes in the
# stage named) and polls /metrics until dot_busy_threads is 0 again. Prints,
# per case, the median and worst of RUNS runs of (server idle - client gave
# up), in ms. The target is ~100 ms of CPU.
#
#   scripts/stop_latency.sh [RUNS]     (default 5; BUILD_DIR=build)
set -euo pipefail
cd "$(dirname "$0")/.."
exec /usr/bin/python3 - "${BUILD_DIR:-build}" "${1:-5}" <<'PY'
import math, os, socket, statistics, subprocess, sys, tempfile, time, urllib.request

build, runs = sys.argv[1], int(sys.argv[2])
dotctl, server_bin = f"{build}/client/dotctl", f"{build}/server/dot-server"
work = tempfile.mkdtemp(prefix="dot-stop-")

def torus(path, nu, nv):
    with open(path, "w") as f:
        f.write(f"OFF\n{nu * nv} {2 * nu * nv} 0\n")
        for i in range(nu):
            for j in range(nv):
                u, v = 2 * math.pi * i / nu, 2 * math.pi * j / nv
                r = 1 + 0.05 * math.sin(7 * u) * math.cos(5 * v)
                x = (3 + r * math.cos(v)) * math.cos(u)
                y = (3 + r * math.cos(v)) * math.sin(u)
                f.write(f"{x} {y} {r * math.sin(v)}\n")
        for i in range(nu):
            for j in range(nv):
                a, b = i * nv + j, i * nv + (j + 1) % nv
                c, d = ((i + 1) % nu) * nv + j, ((i + 1) % nu) * nv + (j + 1) % nv
                f.write(f"3 {a} {c} {d}\n3 {a} {d} {b}\n")

def port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0)); return s.getsockname()[1]

closed = f"{work}/torus.off"
torus(closed, 700, 350)  # 490,000 faces
many = f"{work}/many.off"
one = f"{work}/one.off"
subprocess.run([dotctl, "generate", "holes", closed, "-k", "40", "-t", "300",
                "--seed", "1", "-o", many], check=True, capture_output=True)
subprocess.run([dotctl, "generate", "holes", closed, "-k", "1", "-t", "6000",
                "--seed", "2", "-o", one], check=True, capture_output=True)

grpc_port, metrics_port = port(), port()
server = subprocess.Popen([server_bin, "--listen", f"127.0.0.1:{grpc_port}",
                           "--metrics-port", str(metrics_port),
                           "--log-level", "warn"])
def busy():
    text = urllib.request.urlopen(
        f"http://127.0.0.1:{metrics_port}/metrics", timeout=5).read().decode()
    for line in text.splitlines():
        if line.startswith("dot_busy_threads"):
            return float(line.split()[-1])
    return 0.0

def fill(mesh, timeout, extra):
    t0 = time.monotonic()
    r = subprocess.run([dotctl, "--server", f"127.0.0.1:{grpc_port}",
                        "--timeout", str(timeout), "-q", "fill-holes", mesh,
                        "-o", f"{work}/out.ply", *extra], capture_output=True,
                       text=True)
    return time.monotonic() - t0, r.returncode, r.stderr

meshes = [  # name, mesh, flags
    ("40 holes of 300 faces, 490k-face torus", many, []),
    ("1 hole of 6000 faces, --density 4", one, ["--density", "4"]),
]
try:
    time.sleep(1.0)
    for name, mesh, extra in meshes:
        fulls = []
        for _ in range(3):  # the first call also warms the server up
            t, code, err = fill(mesh, 600, extra)
            assert code == 0, err
            fulls.append(t)
        full = min(fulls)
        print(f"{name}: whole call {1000 * full:.0f} ms (fastest of 3)")
        for fraction in (0.2, 0.5, 0.8):
            timeout = full * fraction
            lags, stopped = [], 0
            for _ in range(runs):
                _, code, err = fill(mesh, timeout, extra)
                gave_up = time.monotonic()
                stopped += "DEADLINE_EXCEEDED" in err
                while busy() > 0:
                    time.sleep(0.002)
                lags.append(1000 * (time.monotonic() - gave_up))
                time.sleep(0.2)
            print(f"  deadline at {100 * fraction:3.0f}% ({1000 * timeout:5.0f} ms): "
                  f"server idle {statistics.median(lags):6.1f} ms after the "
                  f"client gave up (median of {runs}, worst {max(lags):.1f}; "
                  f"{stopped} of {runs} stopped by the deadline)")
finally:
    server.terminate(); server.wait(timeout=60)
PY
