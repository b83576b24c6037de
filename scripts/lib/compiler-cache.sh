# Sourced by the build scripts: compiler caching where ccache is installed
# (scripts/install-deps.sh installs it), so that a fresh clone on a machine that built
# before compiles only what changed. Sets `compiler_cache` to the cmake arguments
# (empty without ccache). The precompiled headers are cached only with ccache's pch
# sloppiness, and CCACHE_BASEDIR makes paths relative so that two clones share hits.
# With debug information (-g: the ThreadSanitizer and clang builds) ccache also hashes
# the build directory's path, so that a clone elsewhere (CI's fresh checkout) would
# miss every object; CCACHE_NOHASHDIR lets it hit, the debug information then naming
# the directory of the clone that compiled the object first (sanitizer reports show
# that path, followed by the right relative one).
compiler_cache=()
if command -v ccache >/dev/null; then
  compiler_cache_launcher="env;CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime;CCACHE_BASEDIR=$PWD;CCACHE_NOHASHDIR=1;ccache"
  compiler_cache=("-DCMAKE_C_COMPILER_LAUNCHER=$compiler_cache_launcher"
    "-DCMAKE_CXX_COMPILER_LAUNCHER=$compiler_cache_launcher")
fi
