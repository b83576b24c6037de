#!/usr/bin/env bash
# Installs what the project needs from Debian 12's packages, and nothing else.
# Safe to run again: it installs only what is missing.
#   scripts/install-deps.sh           what the build, the tests and the bench need
#   scripts/install-deps.sh aarch64   the AArch64 cross build and its emulator
#                                     (scripts/test-aarch64.sh)
#   scripts/install-deps.sh wasm      emscripten and node (scripts/test-wasm.sh)
#   scripts/install-deps.sh web       Chromium, protoc, node and npm (scripts/test-web.sh)
set -euo pipefail

case "${1:-}" in
  aarch64) packages=(g++-aarch64-linux-gnu qemu-user) ;;
  # node: Debian's nodejs where no node is installed yet.
  wasm)
    packages=(emscripten)
    command -v node >/dev/null || packages+=(nodejs)
    ;;
  # The browser the viewer's test drives (through puppeteer-core), protoc for the
  # client's generated code; node and npm where no node is installed yet.
  web)
    packages=(chromium protobuf-compiler)
    command -v node >/dev/null || packages+=(nodejs)
    command -v npm >/dev/null || packages+=(npm)
    ;;
  "") packages=(
  build-essential cmake ninja-build pkg-config
  # Compiler caching (scripts/build.sh uses it where it is installed).
  ccache
  libasio-dev libprotobuf-dev protobuf-compiler
  libgtest-dev libgmock-dev libbenchmark-dev
  # The client's twins' shared test vectors (tests/vectors/*.json), read by the gtests.
  nlohmann-json3-dev
  libcli11-dev libspdlog-dev libfmt-dev
  # The server's /metrics endpoint and its Agones SDK calls (HTTP).
  libcpp-httplib-dev
  # The WebSocket port (header-only).
  libwebsocketpp-dev
  # Connect tickets (shared/ticket: HMAC-SHA-256, base64url).
  libsodium-dev
  # Peer engines, measured beside ours in physics-bench.
  libbox2d-dev libchipmunk-dev
  # Plots in docs/ACCURACY.md.
  gnuplot-nox
  # scripts/test-clang.sh (gcc's hashes with clang) and scripts/test-fuzz.sh (libFuzzer).
  clang-14 libclang-rt-14-dev
  # physics-view: drawing (SDL2), its panel's font and PNG screenshots (stb); its
  # window's test runs under a virtual X server (xvfb).
  libsdl2-dev libstb-dev xvfb
) ;;
  *) echo "usage: scripts/install-deps.sh [aarch64|wasm|web]" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: everything is installed"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
