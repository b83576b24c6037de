#!/usr/bin/env bash
# The installed package as a user gets it: installs the product from the build
# directory into a temporary prefix, builds tests/package/ (a project of its own)
# against that prefix with find_package alone, and runs its tests; then builds one
# program with the pkg-config file's flags alone. The examples (examples/*/) are built
# against the same prefix and their tests run. Builds the build directory first
# (scripts/build.sh when it is not configured yet).
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
build_dir="${BUILD_DIR:-build}"
work="$(mktemp -d "${TMPDIR:-/tmp}/physics-package.XXXXXX")"
trap 'rm -rf "$work"' EXIT

if [ -f "$build_dir/CMakeCache.txt" ]; then
  cmake --build "$build_dir" -j "$(nproc)"
else
  scripts/build.sh
fi
prefix="$work/prefix"
cmake --install "$build_dir" --prefix "$prefix" > "$work/install.log"
for doc in LICENSE CHANGELOG.md; do
  if [ ! -f "$prefix/share/doc/physics_server/$doc" ]; then
    echo "test-package: share/doc/physics_server/$doc is not installed" >&2
    exit 1
  fi
done

# The consumer is copied out of the tree, so that nothing of it can reach back in.
cp -r tests/package "$work/consumer"
cmake -S "$work/consumer" -B "$work/consumer-build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > "$work/configure.log" \
  || { cat "$work/configure.log"; exit 1; }
cmake --build "$work/consumer-build" -j "$(nproc)"
if grep -F "$root" "$work/consumer-build/compile_commands.json" > /dev/null; then
  echo "test-package: the consumer's compile commands name the source tree:" >&2
  grep -F "$root" "$work/consumer-build/compile_commands.json" >&2
  exit 1
fi
ctest --test-dir "$work/consumer-build" --output-on-failure --timeout 120

# The examples (examples/*/), each a game team's own project, against the package:
# built, and their tests (label example) run.
for example in examples/*/; do
  name="$(basename "$example")"
  cmake -S "$example" -B "$work/$name-build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$prefix" > "$work/$name-configure.log" \
    || { cat "$work/$name-configure.log"; exit 1; }
  cmake --build "$work/$name-build" -j "$(nproc)"
  ctest --test-dir "$work/$name-build" --output-on-failure --timeout 120 -L example
done

pc_dir="$(dirname "$(find "$prefix" -name physics_server.pc | head -n 1)")"
# shellcheck disable=SC2046  # the flags are words
c++ -std=c++20 -O1 -o "$work/pkg-config-main" tests/package/pkg_config_main.cpp \
  $(PKG_CONFIG_PATH="$pc_dir" pkg-config --cflags --libs physics_server)
"$work/pkg-config-main"
echo "test-package: the installed package builds and passes its consumer's tests"
