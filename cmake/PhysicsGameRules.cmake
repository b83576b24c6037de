# physics_add_game_rules(<target> <source>...): a game's rules as a shared library
# that physics-server loads (`physics-server --rules $<TARGET_FILE:target>`), from the
# installed package (find_package(physics_server CONFIG) includes this file) or the
# product's own tree.
#
# One of the sources defines the entry point with PHYSICS_GAME_RULES
# (server/rules_plugin.h). The library is a MODULE that gets the server's headers but
# links none of its code: its calls into the server (GameWorld, the physics types)
# bind, when it is loaded, to the copies inside the physics-server that loads it, so
# that the rules and the server share one copy of every type and its vtable. Its own
# symbols are hidden but for the entry point, so that they never collide with the
# server's. Other libraries a game needs it links itself, as usual.
function(physics_add_game_rules target)
  if(NOT ARGN)
    message(FATAL_ERROR "physics_add_game_rules(${target}): no sources")
  endif()
  add_library(${target} MODULE ${ARGN})
  # The rules' API is physics::tick's (server/game_rules.h, server/rules_plugin.h, the
  # core and scene headers they include); an alias in the tree, imported installed.
  set(api physics::tick)
  get_target_property(aliased ${api} ALIASED_TARGET)
  if(aliased)
    set(api ${aliased})
  endif()
  target_include_directories(${target} PRIVATE
    $<TARGET_PROPERTY:${api},INTERFACE_INCLUDE_DIRECTORIES>)
  target_compile_definitions(${target} PRIVATE
    $<TARGET_PROPERTY:${api},INTERFACE_COMPILE_DEFINITIONS>)
  target_compile_features(${target} PRIVATE cxx_std_20)
  set_target_properties(${target} PROPERTIES
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
endfunction()
