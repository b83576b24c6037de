# physics_forbid_asio(TARGET): TARGET's own sources cannot include Asio (standalone,
# Debian's libasio-dev): a folder of poison headers, one of the same name for each of
# Asio's, each an #error, goes first on TARGET's private include path, so that an
# include of any of them, direct or through a header of ours, fails the build with
# the reason. Checked once when the build is configured: a source that includes
# <asio.hpp> with TARGET's include path must fail to compile.
function(physics_forbid_asio target)
  find_path(PHYSICS_ASIO_INCLUDE_DIR asio.hpp)
  if(NOT PHYSICS_ASIO_INCLUDE_DIR)
    return()  # no Asio on this machine (a cross build): nothing to include by mistake
  endif()
  set(poison "${CMAKE_BINARY_DIR}/forbidden-headers/${target}")
  file(GLOB_RECURSE headers RELATIVE "${PHYSICS_ASIO_INCLUDE_DIR}"
    "${PHYSICS_ASIO_INCLUDE_DIR}/asio/*.hpp")
  list(APPEND headers asio.hpp)
  foreach(header IN LISTS headers)
    if(NOT EXISTS "${poison}/${header}")
      file(WRITE "${poison}/${header}"
        "#error \"${target} may not use Asio (<${header}>): it is the tick without a socket; "
        "the network layer is physics_server (docs/SERVER.md, Layout)\"\n")
    endif()
  endforeach()
  target_include_directories(${target} BEFORE PRIVATE "${poison}")
  if(NOT DEFINED PHYSICS_FORBID_ASIO_WORKS_${target})
    set(probe "${CMAKE_BINARY_DIR}/forbidden-headers/${target}-probe.cpp")
    file(WRITE "${probe}" "#include <asio/io_context.hpp>\nint main() { return 0; }\n")
    try_compile(included "${CMAKE_BINARY_DIR}/forbidden-headers/${target}-probe"
      SOURCES "${probe}"
      CMAKE_FLAGS "-DINCLUDE_DIRECTORIES=${poison}"
      CXX_STANDARD 20)
    if(included)
      message(FATAL_ERROR "physics_forbid_asio(${target}): a source that includes Asio "
        "compiled with ${target}'s include path: the poison headers in ${poison} do not work")
    endif()
    set(PHYSICS_FORBID_ASIO_WORKS_${target} TRUE CACHE INTERNAL
      "A source including Asio failed to compile with ${target}'s include path")
  endif()
endfunction()
