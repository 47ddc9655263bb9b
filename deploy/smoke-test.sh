#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# End-to-end check of the container deployment on loopback: builds the
# images, starts 3 dot-server replicas and the nginx load balancer (the
# topology of compose.yaml), load-tests through the balancer, checks that
# every replica served traffic, kills one replica in the middle of a second
# load run and checks the client saw few errors (nginx re-routes, the client
# retries UNAVAILABLE), then tears everything down.
# ENGINE=docker to use Docker; default podman (prepared by
# ../shared/tools/container-env.sh when present).
set -euo pipefail
cd "$(dirname "$0")/.."
engine=${ENGINE:-podman}
if [ "$engine" = podman ] && ! command -v podman >/dev/null && [ -x ../shared/tools/container-env.sh ]; then
  ../shared/tools/container-env.sh >/dev/null
fi
build_flags=()
# podman: host network for apt, Docker image format to keep HEALTHCHECK.
[ "$engine" = podman ] && build_flags=(--network=host --format docker)
image=localhost/dot-server:latest lb_image=localhost/dot-lb:latest
names=(dot-smoke-1 dot-smoke-2 dot-smoke-3 dot-smoke-lb dot-smoke-tls)
network=dot-smoke
say() { printf '\n== %s\n' "$*"; }
cleanup() {  # one at a time: podman's rm gives up on all if one is missing
  for name in "${names[@]}"; do "$engine" rm -f -t 0 "$name" >/dev/null 2>&1 || true; done
  "$engine" network rm "$network" >/dev/null 2>&1 || true
}
trap cleanup EXIT
cleanup

say "building images"
"$engine" build "${build_flags[@]}" -q -t "$image" \
  --build-arg DOT_COMMIT="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)" . >/dev/null
"$engine" build "${build_flags[@]}" -q -t "$lb_image" deploy/nginx >/dev/null
"$engine" image ls --format '{{.Repository}}:{{.Tag}} {{.Size}}' | grep -E 'dot-(server|lb)'

say "starting 3 replicas and the load balancer (the topology of compose.yaml)"
"$engine" network create "$network" >/dev/null
for i in 1 2 3; do
  "$engine" run -d --rm --no-healthcheck --read-only --name "dot-smoke-$i" \
    --network "$network" --network-alias "dot-$i" -p "127.0.0.1:909$i:9090" \
    -e DOT_THREADS=1 -e DOT_LOG_LEVEL=warn "$image" >/dev/null
done
"$engine" run -d --rm --no-healthcheck --name dot-smoke-lb --network "$network" \
  -p 127.0.0.1:8080:8080 "$lb_image" >/dev/null
dotctl() { "$engine" run --rm --no-healthcheck --network=host --entrypoint dotctl "$image" "$@"; }
for i in 1 2 3; do
  for _ in $(seq 100); do
    "$engine" exec "dot-smoke-$i" dotctl health >/dev/null 2>&1 && break
    sleep 0.2
  done
  echo "replica $i: $("$engine" exec "dot-smoke-$i" dotctl health)"
done
for _ in $(seq 50); do dotctl --server 127.0.0.1:8080 health >/dev/null 2>&1 && break; sleep 0.2; done
if ! dotctl --server 127.0.0.1:8080 health; then
  echo "FAIL: the balancer does not answer"; "$engine" logs dot-smoke-lb 2>&1 | tail -5; exit 1
fi

served() {  # requests replica $1 answered, from its Prometheus endpoint
  curl -s "127.0.0.1:909$1/metrics" |
    awk '/^dot_requests_total/ {s += $2} END {print s + 0}'
}

say "load through the balancer: 600 requests, concurrency 6, Monkey n=300"
fail=0
dotctl --server 127.0.0.1:8080 load -c 6 -r 600 -n 300 -d 120 --squared-dihedral 1 ||
  { echo "FAIL: requests failed with every replica up"; fail=1; }
for i in 1 2 3; do
  n=$(served "$i")
  echo "replica $i served $n requests"
  [ "$n" -gt 0 ] || { echo "FAIL: replica $i served nothing"; fail=1; }
done

say "killing replica 2 (SIGKILL) during a second run of 1000 requests"
report=$(mktemp)
dotctl --server 127.0.0.1:8080 load -c 6 -r 1000 -n 300 -d 120 --json >"$report" &
load=$!
sleep 1.5
"$engine" kill --signal KILL dot-smoke-2 >/dev/null
echo "replica 2 killed"
wait "$load" || true
cat "$report"
errors=$(sed -n 's/.*"errors":\([0-9]*\).*/\1/p' "$report")
requests=$(sed -n 's/.*"requests":\([0-9]*\).*/\1/p' "$report")
rm -f "$report"
echo "errors: ${errors:-?} of ${requests:-?} requests"
if [ -z "$errors" ] || [ "$errors" -gt 10 ]; then
  echo "FAIL: too many errors while a replica died"; fail=1
fi
for i in 1 3; do echo "replica $i served $(served "$i") requests in total"; done

say "FillHoles of a mesh over 64 MB through the balancer"
# nginx once reset such streams (client_max_body_size 64m).
big=$(mktemp -d)
/usr/bin/python3 - "$big/grid.off" <<'PY'
import sys
n = 1300  # (n+1)^2 vertices, 2 n^2 faces minus a hole: ~70 MB on the wire
with open(sys.argv[1], "w") as f:
    faces = []
    for i in range(n):
        for j in range(n):
            if n // 2 - 2 <= i < n // 2 + 2 and n // 2 - 2 <= j < n // 2 + 2:
                continue
            a = i * (n + 1) + j
            faces.append(f"3 {a} {a + 1} {a + n + 2}\n3 {a} {a + n + 2} {a + n + 1}\n")
    f.write(f"OFF\n{(n + 1) ** 2} {2 * len(faces)} 0\n")
    f.writelines(f"{i} {j} 0\n" for i in range(n + 1) for j in range(n + 1))
    f.writelines(faces)
PY
chmod -R a+rwX "$big"
if "$engine" run --rm --no-healthcheck --network=host -v "$big:/work:Z" \
    --entrypoint dotctl "$image" --server 127.0.0.1:8080 --timeout 600 \
    fill-holes /work/grid.off --stage triangulate --skip-longest -o /work/out.ply; then
  echo "filled through the balancer: $(du -h "$big/out.ply" | cut -f1) written"
else
  echo "FAIL: a large FillHoles did not pass the balancer"; fail=1
fi
rm -rf "$big"

say "the image's HEALTHCHECK with TLS on the main port (DOT_TLS_* set)"
tls=$(mktemp -d)
openssl req -x509 -newkey rsa:2048 -nodes -keyout "$tls/server.key" \
  -out "$tls/server.crt" -days 2 -subj /CN=localhost \
  -addext subjectAltName=DNS:localhost,IP:127.0.0.1 2>/dev/null
chmod -R a+rX "$tls"
"$engine" run -d --rm --name dot-smoke-tls -v "$tls:/tls:ro,Z" \
  -e DOT_TLS_CERT=/tls/server.crt -e DOT_TLS_KEY=/tls/server.key "$image" >/dev/null
health=unhealthy
for _ in $(seq 50); do  # the image's own check, as the engine runs it
  "$engine" healthcheck run dot-smoke-tls >/dev/null 2>&1 && { health=healthy; break; }
  sleep 0.2
done
echo "container with DOT_TLS_CERT and DOT_TLS_KEY: $health"
[ "$health" = healthy ] || { echo "FAIL: the HEALTHCHECK fails under TLS"; fail=1; }
if "$engine" exec -e DOT_TLS_CERT= -e DOT_TLS_KEY= -e DOT_TLS_CA=/tls/server.crt \
    dot-smoke-tls dotctl --server localhost:50051 health; then
  echo "the TLS port answers a client that trusts its certificate"
else
  echo "FAIL: the TLS port does not answer"; fail=1
fi
"$engine" rm -f -t 0 dot-smoke-tls >/dev/null 2>&1 || true
rm -rf "$tls"

say "tearing down"
cleanup
trap - EXIT
if [ "$fail" = 0 ]; then echo "smoke test PASSED"; else echo "smoke test FAILED"; exit 1; fi
