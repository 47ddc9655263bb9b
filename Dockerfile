# SPDX-License-Identifier: AGPL-3.0-or-later
# dot-server and dotctl. Build: docker build . (or podman build
# --network=host . where no registry is reachable).
ARG DEBIAN=bookworm

FROM debian:${DEBIAN} AS build
RUN apt-get update \
 && apt-get install -y --no-install-recommends \
      cmake ninja-build g++ pkg-config \
      libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler \
      libtet1.5-dev libcgal-dev libeigen3-dev libtbb-dev libspdlog-dev libcli11-dev prometheus-cpp-dev \
 && rm -rf /var/lib/apt/lists/*
WORKDIR /src
COPY . .
ARG DOT_COMMIT=unknown
RUN cmake -S . -B /build -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DDOT_BUILD_TESTS=OFF -DDOT_BUILD_BENCH=OFF -DDOT_GIT_COMMIT=${DOT_COMMIT} \
 && cmake --build /build \
 && DESTDIR=/out cmake --install /build --prefix /usr/local --strip \
      --component Unspecified
# The Corresponding Source, served to users by GetSource (AGPL-3.0 s. 13).
RUN mkdir -p /out/usr/share/dot \
 && tar --exclude=./.git -czf /out/usr/share/dot/dot-source.tar.gz .

FROM debian:${DEBIAN}-slim
ARG DOT_VERSION=0.1.0
ARG DOT_COMMIT=unknown
LABEL org.opencontainers.image.title="dot-server" \
      org.opencontainers.image.description="Optimal intersection-free triangulation of 3D polygons, hole filling and curve networks into surfaces, as a gRPC service (dot-server, dotctl)" \
      org.opencontainers.image.version="${DOT_VERSION}" \
      org.opencontainers.image.revision="${DOT_COMMIT}" \
      org.opencontainers.image.licenses="AGPL-3.0-or-later" \
      org.opencontainers.image.base.name="debian:${DEBIAN}-slim"
RUN apt-get update \
 && apt-get install -y --no-install-recommends \
      libgrpc++1.51 libgrpc29 libprotobuf32 libabsl20220623 libre2-9 \
      libc-ares2 libssl3 zlib1g libtet1.5 libgmp10 libtbb12 libspdlog1.10 libfmt9 \
      libprometheus-cpp-core1.0 libprometheus-cpp-pull1.0 libcivetweb1 \
 && rm -rf /var/lib/apt/lists/* \
 && useradd --system --uid 10001 --no-create-home --shell /usr/sbin/nologin dot
COPY --from=build /out/ /
COPY LICENSE /usr/share/dot/LICENSE
USER 10001
# Metrics on every interface of the container, as EXPOSE says (the
# binary alone binds them to loopback); publishing decides who reaches them.
# glibc.malloc.hugetlb=1: large tables get transparent huge pages; page
# faults otherwise cost up to half of a large solve (README, Performance).
ENV DOT_LISTEN=0.0.0.0:50051 \
    DOT_HEALTH_LISTEN=127.0.0.1:50052 \
    DOT_METRICS_PORT=9090 \
    DOT_METRICS_BIND=0.0.0.0 \
    DOT_LOG_LEVEL=info \
    DOT_DRAIN_SECONDS=20 \
    DOT_SERVER=127.0.0.1:50051 \
    GLIBC_TUNABLES=glibc.malloc.hugetlb=1
EXPOSE 50051 9090
# Health over a plaintext, health-only loopback port (DOT_HEALTH_LISTEN):
# with TLS on the main port, `dotctl health` read the server's DOT_TLS_CERT
# and DOT_TLS_KEY as a client certificate and failed (unhealthy container).
# The client's TLS variables are cleared for the check.
HEALTHCHECK --interval=10s --timeout=4s --start-period=5s --retries=3 \
  CMD ["env", "-u", "DOT_TLS_CA", "-u", "DOT_TLS_CERT", "-u", "DOT_TLS_KEY", \
       "dotctl", "--server", "127.0.0.1:50052", "health"]
STOPSIGNAL SIGTERM
ENTRYPOINT ["dot-server"]
