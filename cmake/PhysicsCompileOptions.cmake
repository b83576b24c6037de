# Compile options every target of ours gets through the physics_options interface.
# Determinism: no -ffast-math, and -ffp-contract=off so that no build type fuses
# a*b+c into an FMA that rounds differently (same scene, same hash, every build).
add_library(physics_options INTERFACE)
target_compile_options(physics_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual -Wnull-dereference
  -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough
  -ffp-contract=off -fno-fast-math)
if(PHYSICS_WARNINGS_AS_ERRORS)
  target_compile_options(physics_options INTERFACE -Werror)
endif()
if(PHYSICS_SANITIZE)
  target_compile_options(physics_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_link_options(physics_options INTERFACE -fsanitize=address,undefined)
endif()
if(PHYSICS_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "PHYSICS_FUZZ needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++-14")
  endif()
  # Coverage for libFuzzer in every library of ours; the harnesses link its main
  # (tests/fuzz/CMakeLists.txt).
  target_compile_options(physics_options INTERFACE
    -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
    -fno-omit-frame-pointer)
  target_link_options(physics_options INTERFACE -fsanitize=address,undefined)
endif()
if(PHYSICS_TSAN)
  # -Wno-tsan: GCC warns that Asio's and libstdc++'s atomic_thread_fence is not
  # instrumented; that is their code, not a race of ours.
  target_compile_options(physics_options INTERFACE -fsanitize=thread -fno-omit-frame-pointer
    -Wno-tsan)
  target_link_options(physics_options INTERFACE -fsanitize=thread)
endif()
