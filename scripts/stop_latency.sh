#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# How long dot-server keeps computing after a FillHoles client gives up:
# starts dot-server (metrics on), makes a bumpy torus with holes (closed mesh
# from Python, holes cut by `dotctl generate holes`), a sphere with one
# large round hole and a strip around a 20,000-vertex hole, then for each case
# runs `dotctl fill-holes --timeout T` (the client's deadline passes in the
# stage named) and polls /metrics until dot_busy_threads is 0 again. Prints,
# per case, the median and worst of RUNS runs of (server idle - client gave
# up), in ms. The target is ~100 ms of CPU.
#
#   scripts/stop_latency.sh [RUNS]     (default 5; BUILD_DIR=build)
set -euo pipefail
cd "$(dirname "$0")/.."
exec /usr/bin/python3 - "${BUILD_DIR:-build}" "${1:-5}" <<'PY'
import json, math, os, socket, statistics, subprocess, sys, tempfile, time, urllib.request

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

def sphere_with_cap_cut(path, rings, segments, cut_x):
    """A UV sphere without the faces whose centroid has x > cut_x: one round
    hole whose refined patch is large (its fairing system ~12,000 unknowns
    at 256 x 512)."""
    v = [(0.0, 0.0, 1.0)]
    for i in range(1, rings):
        t = math.pi * i / rings
        for j in range(segments):
            p = 2 * math.pi * j / segments
            v.append((math.sin(t) * math.cos(p), math.sin(t) * math.sin(p),
                      math.cos(t)))
    v.append((0.0, 0.0, -1.0))
    south = len(v) - 1
    ident = lambda i, j: 1 + (i - 1) * segments + j % segments
    faces = []
    for j in range(segments):
        faces.append((0, ident(1, j), ident(1, j + 1)))
        faces.append((south, ident(rings - 1, j + 1), ident(rings - 1, j)))
    for i in range(1, rings - 1):
        for j in range(segments):
            faces.append((ident(i, j), ident(i + 1, j), ident(i + 1, j + 1)))
            faces.append((ident(i, j), ident(i + 1, j + 1), ident(i, j + 1)))
    faces = [f for f in faces if sum(v[k][0] for k in f) / 3 <= cut_x]
    with open(path, "w") as out:
        out.write(f"OFF\n{len(v)} {len(faces)} 0\n")
        out.writelines(f"{x!r} {y!r} {z!r}\n" for x, y, z in v)
        out.writelines(f"3 {a} {b} {c}\n" for a, b, c in faces)

def wavy_strip(path, k):
    """A closed strip around one hole of k boundary vertices: the hole's
    patch of ~2k faces dominates the intersection check."""
    with open(path, "w") as out:
        out.write(f"OFF\n{2 * k} {2 * k} 0\n")
        for r in (1.0, 1.2):
            for i in range(k):
                a = 2 * math.pi * i / k
                out.write(f"{r * math.cos(a)!r} {r * math.sin(a)!r} "
                          f"{0.2 * math.sin(9 * a)!r}\n")
        for i in range(k):
            j = (i + 1) % k
            out.write(f"3 {i} {k + i} {k + j}\n3 {i} {k + j} {j}\n")

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

cap = f"{work}/cap.off"
sphere_with_cap_cut(cap, 256, 512, 0.75)
strip = f"{work}/strip.off"
wavy_strip(strip, 20000)

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
    """The call's own latency (not dotctl's reading and writing of files),
    its exit code, and its JSON outcome."""
    r = subprocess.run([dotctl, "--server", f"127.0.0.1:{grpc_port}",
                        "--timeout", str(timeout), "fill-holes", mesh,
                        "--json", "-o", f"{work}/out.ply", *extra],
                       capture_output=True, text=True)
    outcome = json.loads(r.stdout)
    return outcome["latency_ms"] / 1000, r.returncode, outcome

meshes = [  # name, mesh, flags
    ("40 holes of 300 faces, 490k-face torus", many, []),
    ("1 hole of 6000 faces, --density 4", one, ["--density", "4"]),
    ("sphere cap of 470 boundary vertices (6,800 faired in a helper)", cap,
     []),
    ("1 hole of 20,000 boundary vertices (its inner rim)", strip,
     ["--holes", "0"]),
]
try:
    time.sleep(1.0)
    for name, mesh, extra in meshes:
        fulls = []
        for _ in range(5):  # the first two calls warm the server up
            t, code, outcome = fill(mesh, 600, extra)
            assert code == 0, outcome
            fulls.append(t)
        full = statistics.median(fulls[2:])
        print(f"{name}: whole call {1000 * full:.0f} ms (the RPC's latency, "
              f"median of 3 after 2 warm-up calls)")
        for fraction in (0.2, 0.5, 0.8):
            timeout = full * fraction
            lags, stopped = [], 0
            for _ in range(runs):
                _, code, outcome = fill(mesh, timeout, extra)
                gave_up = time.monotonic()
                stopped += outcome["rpc_status"] == "DEADLINE_EXCEEDED"
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
