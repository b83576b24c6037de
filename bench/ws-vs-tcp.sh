#!/usr/bin/env bash
# The WebSocket port against the TCP port on the server's side: bytes on the wire and
# server CPU per tick, 64 clients driving their bodies on moving-1000, one client
# program on both ports, in one node process (client/web/client/bench/: the light
# client of light-client.mjs, over the `ws` package or over a plain TCP connection
# with the varint framing of docs/PROTOCOL.md 1.1, tcp-socket.mjs). ws-vs-tcp.mjs
# there says what each client does and what each column is. The two cases take turns,
# ROUNDS rounds (default 2); the last row is the ratio ws/tcp. Builds the package
# first (npm ci and npm run build, as scripts/test-web.sh does) when its dist/ is
# missing. CLIENT_PROGRAM=full plays @physics/client's Client instead (too slow for
# 64 at 60 Hz in one process on 2 cores).
#   bench/ws-vs-tcp.sh                                  64 clients, 20 s after 3 s
#   CLIENTS=4 DURATION=3 ROUNDS=1 OUT=/tmp/w.csv bench/ws-vs-tcp.sh   a quick look
# The server is $PHYSICS_SERVER, or $BUILD_DIR/server/physics-server (BUILD_DIR
# defaults to build/). Writes bench/results/ws-vs-tcp.csv (OUT=FILE writes there
# instead).
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
out="$(realpath -m "${OUT:-bench/results/ws-vs-tcp.csv}")"
server="$(realpath -m "${PHYSICS_SERVER:-${BUILD_DIR:-build}/server/physics-server}")"
[[ -x "$server" ]] || { echo "ws-vs-tcp: no $server (ninja -C build physics-server)" >&2; exit 1; }
package=client/web/client
if [ ! -f "$package/dist/index.js" ]; then
  (cd "$package" && npm ci --no-audit --no-fund --loglevel=error && npm run --silent build)
fi
trap 'rm -f "$out.tmp"' EXIT
echo "ws-vs-tcp: node $(node --version), $(nproc) cores, load average: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
(cd "$package" && node bench/ws-vs-tcp.mjs "$server" "$root/scenes/moving-1000.textproto" "$out.tmp" \
  "${CLIENTS:-64}" "${DURATION:-20}" "${WARMUP:-3}" "${ROUNDS:-2}") >/dev/null
mv "$out.tmp" "$out"
echo "ws-vs-tcp: load average after: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
cat "$out"
