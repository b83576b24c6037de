# Precompiled headers for the targets whose files all parse the same heavy headers.
# A file of the server or of its tests spends about 60% of its compile time parsing
# Asio, the generated wire schema, GoogleTest and spdlog; parsing them once a target
# instead of once a file is most of a clean build's time on two cores (CI).
#
# physics_precompile_headers(target [ASIO] [WIRE] [GTEST] [SPDLOG] [SKIP file...])
# With GCC, the target also builds without -Warray-bounds, -Wstringop-overflow,
# -Wstringop-overread and -Wrestrict: GCC 12 loses the system-header mark of
# precompiled code once it is inlined, and those optimizer warnings then fire inside
# libstdc++'s own string code (a false positive the same file without a precompiled
# header does not get). Out-of-bounds accesses are checked at run time instead, by
# AddressSanitizer in CI (scripts/test-asan.sh).
# SKIP: files compiled with flags the header cannot be shared with (the C++17
# WebSocket files) or that include Asio through another library's configuration.
# -DPHYSICS_PRECOMPILE_HEADERS=OFF builds without them: each file then has to include
# what it uses on its own, which that build checks.
option(PHYSICS_PRECOMPILE_HEADERS "Precompile the heavy headers of the server and its tests" ON)

function(physics_precompile_headers target)
  if(NOT PHYSICS_PRECOMPILE_HEADERS)
    return()
  endif()
  cmake_parse_arguments(PCH "ASIO;WIRE;GTEST;SPDLOG" "" "SKIP" ${ARGN})
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-array-bounds -Wno-stringop-overflow
      -Wno-stringop-overread -Wno-restrict)
  endif()
  set(headers <algorithm> <chrono> <cstdint> <functional> <map> <memory> <optional>
    <string> <vector>)
  if(PCH_ASIO)
    list(APPEND headers <asio.hpp>)
  endif()
  if(PCH_WIRE)
    list(APPEND headers <wire.pb.h>)
  endif()
  if(PCH_GTEST)
    list(APPEND headers <gtest/gtest.h>)
  endif()
  if(PCH_SPDLOG)
    list(APPEND headers <spdlog/spdlog.h>)
  endif()
  target_precompile_headers(${target} PRIVATE ${headers})
  if(PCH_SKIP)
    set_source_files_properties(${PCH_SKIP} TARGET_DIRECTORY ${target}
      PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
  endif()
endfunction()
