#!/usr/bin/env bash
# Determinism on AArch64: builds the core, the scene library and physics-hashes alone
# (no Protobuf) with Debian's g++-aarch64-linux-gnu, static, into build-aarch64/, runs
# them under qemu-aarch64, and compares with the native x86-64 build, world by
# world: every scene in scenes/ after 600 steps (as physics-sim runs it, loaded from
# physics-flatten's flat world), the determinism scene, the scene library's golden
# worlds and a hash of det_math's results. Fails on any difference. Installs the
# cross compiler and qemu-user when missing (scripts/install-deps.sh aarch64).
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/lib/cross-hashes.sh
source scripts/lib/compiler-cache.sh
cross_dir="${AARCH64_BUILD_DIR:-build-aarch64}"
work="$cross_dir/hashes"

bash scripts/install-deps.sh aarch64
native_hashes "$work"

cmake -S . -B "$cross_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_SYSTEM_NAME=Linux -DCMAKE_SYSTEM_PROCESSOR=aarch64 \
  -DCMAKE_C_COMPILER=aarch64-linux-gnu-gcc -DCMAKE_CXX_COMPILER=aarch64-linux-gnu-g++ \
  -DCMAKE_EXE_LINKER_FLAGS=-static -DPHYSICS_CORE_ONLY=ON \
  -DPHYSICS_BUILD_TESTS=OFF -DPHYSICS_BUILD_BENCH=OFF -DPHYSICS_WARNINGS_AS_ERRORS=ON \
  "${compiler_cache[@]}"
cmake --build "$cross_dir" -j "$(nproc)" --target physics-hashes

runner=("qemu-aarch64" "$cross_dir/portable/physics-hashes")
[ "$(od -An -tx1 -j18 -N2 "${runner[1]}" | tr -d " ")" = b700 ] || { echo "not an AArch64 binary: ${runner[1]}" >&2; exit 1; }
"${runner[@]}" --steps "$steps" "$work"/flat/*.json >"$work/aarch64.txt"
"${runner[@]}" --library >>"$work/aarch64.txt"
echo "state hashes: x86-64 (native) against AArch64 (qemu-aarch64)"
compare_hashes aarch64 "$work/native.txt" "$work/aarch64.txt"
