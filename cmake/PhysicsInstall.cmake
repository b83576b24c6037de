# Install rules and the CMake package `physics_server` (find_package(physics_server
# CONFIG) -> physics::core, physics::client, physics::server, physics::testing, and the
# executables as physics::physics-server, ...).
#
# A folder that declares a library or tool users get calls, after declaring it:
#   physics_install_library(physics_foo EXPORT_NAME foo HEADERS include)
#   physics_install_executable(physics-foo)
# Every library an installed library links, PUBLIC or PRIVATE, must be installed too:
# the libraries are static, so a consumer links their dependencies itself (CMake
# reports "requires target X that is not in any export set" otherwise).
# The top-level CMakeLists.txt calls physics_install_package() once, at the end.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# Headers go under include/physics_server/ and are included as in the source tree
# ("server/server.h", "physics/world.h", "wire.pb.h"): the short folder names stay
# out of the system include directory.
set(PHYSICS_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/physics_server)
set(PHYSICS_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/physics_server)
set(PHYSICS_EXPORT_SET physics_server_targets)

# physics_install_library(target [EXPORT_NAME name] [HEADERS dir...] [HEADER_FILES file...])
# HEADERS: folders whose *.h files are installed with their relative paths (a build
# folder works too: proto/ installs its generated *.pb.h so);
# HEADER_FILES: single headers installed at the include root.
# Also defines the alias physics::NAME in the tree. The target's include directories, absolute paths of the source or build tree, are
# marked as build-tree only; installed, the target includes the installed headers.
function(physics_install_library target)
  cmake_parse_arguments(arg "" "EXPORT_NAME" "HEADERS;HEADER_FILES" ${ARGN})
  set(exported ${target})
  if(arg_EXPORT_NAME)
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${arg_EXPORT_NAME})
    set(exported ${arg_EXPORT_NAME})
  endif()
  # The package's name in the tree too, so that a project built here (examples/)
  # links the same names as one built against the installed package.
  add_library(physics::${exported} ALIAS ${target})
  get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
  if(dirs)
    set(wrapped "")
    foreach(dir IN LISTS dirs)
      if(dir MATCHES "^\\$<")
        list(APPEND wrapped "${dir}")
      else()
        list(APPEND wrapped "$<BUILD_INTERFACE:${dir}>")
      endif()
    endforeach()
    set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${wrapped}")
  endif()
  get_target_property(type ${target} TYPE)
  if(NOT type STREQUAL "INTERFACE_LIBRARY")
    set_property(GLOBAL APPEND PROPERTY PHYSICS_INSTALLED_LIBRARIES ${target})
  endif()
  install(TARGETS ${target} EXPORT ${PHYSICS_EXPORT_SET}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
    INCLUDES DESTINATION ${PHYSICS_INSTALL_INCLUDEDIR})
  foreach(dir IN LISTS arg_HEADERS)
    install(DIRECTORY ${dir}/ DESTINATION ${PHYSICS_INSTALL_INCLUDEDIR}
      FILES_MATCHING PATTERN "*.h" PATTERN "CMakeFiles" EXCLUDE)
  endforeach()
  if(arg_HEADER_FILES)
    install(FILES ${arg_HEADER_FILES} DESTINATION ${PHYSICS_INSTALL_INCLUDEDIR})
  endif()
endfunction()

# physics_install_executable(target...): installed to bin/ and exported, so that a
# consumer finds the path of, say, the server as $<TARGET_FILE:physics::physics-server>.
function(physics_install_executable)
  install(TARGETS ${ARGN} EXPORT ${PHYSICS_EXPORT_SET}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# The package files: targets, config (with find_dependency for what the static
# libraries link), version, and a pkg-config file for builds without CMake.
function(physics_install_package)
  install(EXPORT ${PHYSICS_EXPORT_SET}
    NAMESPACE physics::
    FILE physics_server-targets.cmake
    DESTINATION ${PHYSICS_INSTALL_CMAKEDIR})
  configure_package_config_file(
    ${PROJECT_SOURCE_DIR}/cmake/physics_server-config.cmake.in
    ${PROJECT_BINARY_DIR}/physics_server-config.cmake
    INSTALL_DESTINATION ${PHYSICS_INSTALL_CMAKEDIR})
  write_basic_package_version_file(
    ${PROJECT_BINARY_DIR}/physics_server-config-version.cmake
    COMPATIBILITY SameMinorVersion)
  install(FILES
    ${PROJECT_BINARY_DIR}/physics_server-config.cmake
    ${PROJECT_BINARY_DIR}/physics_server-config-version.cmake
    DESTINATION ${PHYSICS_INSTALL_CMAKEDIR})
  # The .pc file names its prefix relative to itself, so that it stays right under
  # `cmake --install --prefix DIR`. Its -l flags are the installed libraries in
  # reverse order of declaration: each folder declares its library after the ones it
  # links, so the reverse is an order a static link accepts. Requires: lists what
  # they link from outside (cmake/physics_server.pc.in).
  get_property(libraries GLOBAL PROPERTY PHYSICS_INSTALLED_LIBRARIES)
  list(REVERSE libraries)
  set(PHYSICS_PC_LIBS "")
  foreach(library IN LISTS libraries)
    get_target_property(name ${library} OUTPUT_NAME)
    if(NOT name)
      set(name ${library})
    endif()
    string(APPEND PHYSICS_PC_LIBS " -l${name}")
  endforeach()
  string(REGEX REPLACE "[^/]+" ".." PHYSICS_PC_TO_PREFIX "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
  configure_file(${PROJECT_SOURCE_DIR}/cmake/physics_server.pc.in
    ${PROJECT_BINARY_DIR}/physics_server.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/physics_server.pc
    DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
  # The licence (MIT) and the changes, protocol versions included, beside the package.
  install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CHANGELOG.md
    DESTINATION ${CMAKE_INSTALL_DOCDIR})
endfunction()

# physics_options (PhysicsCompileOptions.cmake) is linked PRIVATE by every library of
# ours; a static library still names its private links in its export, so it is
# exported too. Its compile options (our warnings, -Werror) are for our build alone; a
# consumer gets its link options (the sanitizers', in a sanitized build).
get_target_property(physics_build_options physics_options INTERFACE_COMPILE_OPTIONS)
set_target_properties(physics_options PROPERTIES
  INTERFACE_COMPILE_OPTIONS "$<BUILD_INTERFACE:${physics_build_options}>")
physics_install_library(physics_options EXPORT_NAME options)
