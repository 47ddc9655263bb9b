#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Soak test: dot-server on loopback under a mixed, rate-limited load for a
# while (default 30 minutes), sampling every second the server's and its
# helpers' RSS, open fds and threads, and the helper count. Prints the
# averages of an early minute (the 6th in long runs, after warm-up) and of
# the last, and the peaks; exits 1 when a resource grew (last minute more
# than 20% + a small margin above the early one) or the server died.
# usage: scripts/soak.sh [SECONDS] [OUT.csv]     (binaries from build/)
set -euo pipefail
cd "$(dirname "$0")/.."
duration=${1:-1800}
csv=${2:-soak.csv}
bin=${BUILD_DIR:-build}
server=$bin/server/dot-server
dotctl=$bin/client/dotctl
port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])')
addr=127.0.0.1:$port
work=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  kill "$server_pid" 2>/dev/null || true
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

# A small --malloc-keep-mb: freed memory the allocator keeps for the next
# requests (512 MiB by default) would hide a leak under its plateau.
"$server" --listen "$addr" --metrics-port 0 --threads 2 --log-level warn \
  --malloc-keep-mb 32 \
  >"$work/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 50); do "$dotctl" --server "$addr" health >/dev/null 2>&1 && break; sleep 0.1; done

# Test data: curves and a mesh with holes.
"$dotctl" generate curve spiral -n 3000 -o "$work/spiral.xyz" >/dev/null
"$dotctl" generate holes "$bin/data/meshes/elephant.off" -k 6 -t 150 \
  -o "$work/holey.off" >/dev/null

end=$((SECONDS + duration))
# Mixed load, each loop bounded by the run's end: small and medium polygons
# at a fixed rate, large ones with deadlines that expire, calls cancelled by
# short client timeouts, batch streams, and hole filling.
# `pause` seconds between runs keeps the whole load to about one core.
loop() {
  local pause=$1
  shift
  while ((SECONDS < end)); do
    "$@" >/dev/null 2>&1 || true
    sleep "$pause"
  done
}
loop 0 "$dotctl" --server "$addr" load -c 4 --rate 20 -d 60 -r 1200 -n 100 --curve monkey &
pids+=($!)
loop 0 "$dotctl" --server "$addr" load -c 2 --rate 4 -d 60 -r 240 -n 1000 --curve mobius --no-cache &
pids+=($!)
loop 0 "$dotctl" --server "$addr" load -c 1 --rate 1 -d 60 -r 60 -n 3000 --curve spiral --time-budget-ms 20 &
pids+=($!)
loop 0.5 "$dotctl" --server "$addr" --timeout 0.05 triangulate "$work/spiral.xyz" --squared-dihedral 1 -o "$work/x.obj" &
pids+=($!)
loop 5 "$dotctl" --server "$addr" load -c 4 --batch -d 60 -r 400 -n 200 --curve twist --space delaunay &
pids+=($!)
loop 0 "$dotctl" --server "$addr" load -c 2 --rate 2 -d 60 -r 120 -n 500 --curve moment --delaunay tetgen --no-cache &
pids+=($!)
loop 2 "$dotctl" --server "$addr" fill-holes "$work/holey.off" -q -o "$work/filled.ply" &
pids+=($!)

echo "t,rss_kb,helper_rss_kb,fds,threads,helpers" >"$csv"
status() { awk -v k="$2:" '$1 == k { print $2 }' "/proc/$1/status" 2>/dev/null || echo 0; }
t=0
while ((SECONDS < end)); do
  if ! kill -0 "$server_pid" 2>/dev/null; then
    echo "soak: dot-server died after ${t}s" >&2
    tail -20 "$work/server.log" >&2
    exit 1
  fi
  helpers=$(pgrep -P "$server_pid" || true)
  helper_rss=0
  for h in $helpers; do helper_rss=$((helper_rss + $(status "$h" VmRSS))); done
  echo "$t,$(status "$server_pid" VmRSS),$helper_rss,$(ls "/proc/$server_pid/fd" | wc -l),$(status "$server_pid" Threads),$(echo "$helpers" | grep -c . || true)" >>"$csv"
  sleep 1
  t=$((t + 1))
done
for p in "${pids[@]}"; do wait "$p" 2>/dev/null || true; done
"$dotctl" --server "$addr" health >/dev/null || { echo "soak: unhealthy at the end" >&2; exit 1; }

/usr/bin/python3 - "$csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
cols = ["rss_kb", "helper_rss_kb", "fds", "threads", "helpers"]
# After a warm-up (the first large requests set the allocator's level):
# minute 5 against the last minute, or the first against the last in short
# runs.
warm = 300 if len(rows) >= 900 else 0
first, last = rows[warm:warm + 60], rows[-60:]
avg = lambda rs, c: sum(float(r[c]) for r in rs) / max(1, len(rs))
grew = []
print(f"soak: {len(rows)} samples")
print(f"{'':14}{'minute ' + str(warm // 60 + 1):>12}{'last min':>12}{'peak':>12}")
for c in cols:
    a, b, p = avg(first, c), avg(last, c), max(float(r[c]) for r in rows)
    print(f"{c:14}{a:12.0f}{b:12.0f}{p:12.0f}")
    margin = {"rss_kb": 65536, "helper_rss_kb": 65536}.get(c, 8)
    if b > 1.2 * a + margin:
        grew.append(c)
if grew:
    print("soak: grew:", ", ".join(grew))
    sys.exit(1)
print("soak: flat")
PY
