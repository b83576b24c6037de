# physics-server in a container: built on Debian 12, run on Debian 12 slim as a
# non-root user, listening on 0.0.0.0:7777 (TCP, the game) and 0.0.0.0:9100 (HTTP,
# /healthz, /readyz, /metrics). docs/DEPLOY.md.
#   docker build -t physics-server .
#   docker run --rm -p 7777:7777 -p 9100:9100 physics-server

FROM debian:12-slim AS build
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
      build-essential cmake ninja-build pkg-config \
      libasio-dev libprotobuf-dev protobuf-compiler \
      libcli11-dev libspdlog-dev libfmt-dev libcpp-httplib-dev libwebsocketpp-dev \
      libsodium-dev \
 && rm -rf /var/lib/apt/lists/*
WORKDIR /src
COPY . .
RUN cmake -S . -B /build -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DPHYSICS_BUILD_TESTS=OFF -DPHYSICS_BUILD_BENCH=OFF \
 && cmake --build /build --target physics-server physics-client physics-ticket

FROM debian:12-slim
# The shared libraries the programs link (Debian 12's packages), and curl for
# the health check.
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
      libprotobuf32 libspdlog1.10 libfmt9 libcpp-httplib0.11 libsodium23 curl ca-certificates \
 && rm -rf /var/lib/apt/lists/* \
 && useradd --system --uid 10001 --no-create-home --shell /usr/sbin/nologin physics
COPY --from=build /build/server/physics-server /usr/local/bin/physics-server
COPY --from=build /build/client/physics-client /usr/local/bin/physics-client
COPY --from=build /build/server/ticket/physics-ticket /usr/local/bin/physics-ticket
COPY scenes /usr/local/share/physics/scenes
USER physics
EXPOSE 7777/tcp 9100/tcp
HEALTHCHECK --interval=10s --timeout=2s --start-period=5s --retries=3 \
  CMD curl --fail --silent --max-time 2 http://127.0.0.1:9100/healthz || exit 1
ENTRYPOINT ["/usr/local/bin/physics-server", "--bind", "0.0.0.0", "--port", "7777", \
            "--metrics-port", "9100", "--log-format", "json"]
