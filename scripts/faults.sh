#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Fault tests on loopback, each bounded in time: TetGen helpers killed idle
# and busy, a client killed mid-call, a slow reader, SIGTERM under load
# (every unfinished call must end UNAVAILABLE), and one of two replicas
# killed under load (zero failed calls after the client's retries). Prints
# one line per fault and exits 1 if any expectation fails.
# usage: scripts/faults.sh     (binaries from build/)
set -uo pipefail
cd "$(dirname "$0")/.."
bin=${BUILD_DIR:-build}
server=$bin/server/dot-server
dotctl=$bin/client/dotctl
work=$(mktemp -d)
failures=0
servers=()
trap 'for p in "${servers[@]}"; do kill -9 "$p" 2>/dev/null; wait "$p" 2>/dev/null; done; rm -rf "$work"' EXIT

free_port() {
  /usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'
}
start_server() {  # ADDRESS [flags...]; sets $pid
  local address=$1
  shift
  "$server" --listen "$address" --log-level warn "$@" >>"$work/server.log" 2>&1 &
  pid=$!
  servers+=("$pid")
  for _ in $(seq 100); do
    "$dotctl" --server "$address" health >/dev/null 2>&1 && return 0
    sleep 0.1
  done
  echo "server on $address did not start" >&2
  return 1
}
report() {  # NAME OK(0/1) DETAIL
  if [ "$2" = 0 ]; then
    printf '%-34s ok    %s\n' "$1" "$3"
  else
    printf '%-34s FAIL  %s\n' "$1" "$3"
    failures=$((failures + 1))
  fi
}
json_field() {  # JSON KEY -> value (python, Debian's interpreter)
  /usr/bin/python3 -c 'import json,sys; d=json.loads(sys.argv[1]); print(eval("d"+sys.argv[2]))' "$1" "$2"
}

"$dotctl" generate curve moment -n 400 -o "$work/small.xyz" >/dev/null
"$dotctl" generate curve spiral -n 30000 -o "$work/big.xyz" >/dev/null

# 1-2. TetGen helpers.
port=$(free_port)
a=127.0.0.1:$port
start_server "$a" --delaunay-helpers 1 --metrics-port 0
tetgen() { "$dotctl" --server "$a" triangulate "$1" --delaunay tetgen --no-cache -o "$work/t.obj" 2>&1; }
tetgen "$work/small.xyz" >/dev/null
helper=$(pgrep -P "$pid" | head -1)
kill -9 "$helper" 2>/dev/null
sleep 0.2
out=$(tetgen "$work/small.xyz")
report "helper killed while idle" $([[ $out == *": ok:"* ]] && echo 0 || echo 1) "next call: ${out#*: }"
tetgen "$work/big.xyz" >"$work/busy.txt" &
caller=$!
sleep 1.5
kill -9 "$(pgrep -P "$pid" | head -1)" 2>/dev/null
wait "$caller"
busy=$(tr -d '\n' <"$work/busy.txt")
out=$(tetgen "$work/small.xyz")
report "helper killed mid-request" $([[ $busy == *killed* && $out == *": ok:"* ]] && echo 0 || echo 1) \
  "that call: ${busy#*: }; next: ${out#*: }"

# 3. A client killed mid-call: the server stops the work and serves on.
mport=$(free_port)
kill "$pid"
wait "$pid" 2>/dev/null
# Small chunks: the slow reader below gets many messages.
start_server "$a" --metrics-port "$mport" --metrics-bind 127.0.0.1 --chunk-kb 16
"$dotctl" --server "$a" triangulate "$work/big.xyz" --squared-dihedral 1 --no-cache -o "$work/k.obj" >/dev/null 2>&1 &
caller=$!
sleep 0.5
kill -9 "$caller"
wait "$caller" 2>/dev/null
inflight=1
for _ in $(seq 50); do
  inflight=$(curl -s "127.0.0.1:$mport/metrics" | awk '/^dot_inflight_requests /{print $2}')
  [ "${inflight%.*}" = 0 ] && break
  sleep 0.1
done
out=$("$dotctl" --server "$a" triangulate "$work/small.xyz" -o "$work/s.obj" 2>&1)
report "client killed mid-call" $([[ ${inflight%.*} == 0 && $out == *": ok:"* ]] && echo 0 || echo 1) \
  "in flight afterwards: $inflight; next call ok"

# 4. A slow reader holds a large answer; others are served meanwhile.
/usr/bin/python3 - "$a" "$work/big.xyz" >"$work/slow.txt" 2>&1 <<'PY' &
import struct, sys, time, grpc
def varint(n):
    out = b""
    while True:
        b = n & 0x7F; n >>= 7
        out += bytes([b | (0x80 if n else 0)])
        if not n: return out
def field(k, payload): return varint(k << 3 | 2) + varint(len(payload)) + payload
pts = [tuple(map(float, l.split()[:3])) for l in open(sys.argv[2]) if l.strip()]
coords = b"".join(struct.pack("<d", c) for p in pts for c in p)
options = varint(9 << 3) + varint(1)  # Options.no_cache = true
request = field(1, b"slow") + field(2, field(1, coords)) + field(4, options)
channel = grpc.insecure_channel(sys.argv[1])
call = channel.unary_stream("/dot.v1.Triangulator/Triangulate",
                            request_serializer=lambda b: b,
                            response_deserializer=lambda b: b)
n = 0
for _ in call(request, timeout=60):
    n += 1
    time.sleep(0.05)
print("slow reader got", n, "messages")
PY
slow=$!
sleep 2
t0=$(date +%s.%N)
out=$("$dotctl" --server "$a" --timeout 5 triangulate "$work/small.xyz" -o "$work/s2.obj" 2>&1)
t1=$(date +%s.%N)
wait "$slow"
report "slow reader" $([[ $out == *": ok:"* ]] && grep -q "got" "$work/slow.txt" && echo 0 || echo 1) \
  "$(cat "$work/slow.txt"); another call meanwhile took $(printf '%.2f' "$(echo "$t1 - $t0" | bc)") s"

# 5. SIGTERM under load: unfinished calls end UNAVAILABLE, never CANCELLED.
"$dotctl" --server "$a" load -c 8 -r 100000 -d 20 -n 3000 --curve mobius --no-cache --json >"$work/term.json" 2>/dev/null &
loader=$!
sleep 2
kill -TERM "$pid"
wait "$loader"
statuses=$(json_field "$(cat "$work/term.json")" "['by_status']")
bad=$(/usr/bin/python3 -c 'import json,sys; d=json.load(open(sys.argv[1]))["by_status"]; print(sum(v for k,v in d.items() if k not in ("OK","UNAVAILABLE")))' "$work/term.json")
report "SIGTERM under load" $([ "$bad" = 0 ] && echo 0 || echo 1) "statuses: $statuses"
wait "$pid" 2>/dev/null

# 6. Two replicas (127.0.0.1 and [::1], one name: localhost); one killed.
port=$(free_port)
start_server "127.0.0.1:$port" --metrics-port 0
first=$pid
start_server "[::1]:$port" --metrics-port 0
"$dotctl" --server "localhost:$port" load -c 8 -r 100000 -d 6 -n 300 --curve monkey --no-cache --json >"$work/replica.json" 2>/dev/null &
loader=$!
sleep 2
kill -9 "$first"
wait "$loader"
wait "$first" 2>/dev/null
errors=$(json_field "$(cat "$work/replica.json")" "['errors']")
total=$(json_field "$(cat "$work/replica.json")" "['requests']")
report "replica killed under load" $([ "$errors" = 0 ] && echo 0 || echo 1) \
  "$errors failed of $total calls ($(json_field "$(cat "$work/replica.json")" "['by_status']"))"

echo "faults: $failures failed"
exit $((failures > 0))
