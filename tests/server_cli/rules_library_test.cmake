# Rules libraries physics-server refuses: each exits 2, before listening, with a
# message on stderr that names the file and says what is wrong with it.
#   cmake -DSERVER=... -DVERSION=... -DWORK=DIR -DNO_ENTRY_POINT=... -DWRONG_VERSION=...
#         -DWRONG_ABI=... -DTHROWING_FACTORY=... -DNULL_FACTORY=... -P rules_library_test.cmake

# expect_refused(<what> <stderr regex> <library>)
function(expect_refused what expected library)
  execute_process(COMMAND ${SERVER} --port 0 --rules ${library} RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 30)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "${what}: exit ${rc}, expected 2\nstdout: ${out}\nstderr: ${err}")
  endif()
  if(NOT err MATCHES "${expected}")
    message(FATAL_ERROR "${what}: stderr does not say '${expected}':\n${err}")
  endif()
  if(out MATCHES "listening on")
    message(FATAL_ERROR "${what}: the server listened before refusing the rules:\n${out}")
  endif()
  if(err MATCHES "terminate called|Aborted")
    message(FATAL_ERROR "${what}: aborted\n${err}")
  endif()
endfunction()

file(MAKE_DIRECTORY ${WORK})
set(text_file ${WORK}/not-a-library.so)
# Longer than an ELF header, so that the loader reads it as one and finds it wrong.
file(WRITE ${text_file} "# my game's rules\nThese are notes about the rules, not a shared library: "
     "the loader must say that it cannot load them, and the server must not start.\n")

expect_refused("missing file" "^physics-server: rules library ${WORK}/missing.so: no such file"
               ${WORK}/missing.so)
expect_refused("a folder" "rules library ${WORK}: not a regular file" ${WORK})
expect_refused("text file"
               "rules library ${text_file}: the dynamic loader cannot load it: .*invalid ELF header"
               ${text_file})
expect_refused("no entry point"
               "rules library .*no_entry_point.*: no entry point physics_game_rules_v1 \\(define it with PHYSICS_GAME_RULES"
               ${NO_ENTRY_POINT})
expect_refused("wrong version"
               "built against physics_server 0\\.0\\.1, this physics-server is ${VERSION}: rebuild it"
               ${WRONG_VERSION})
expect_refused("wrong plugin ABI" "built for rules plugin ABI 2, this physics-server loads ABI 1"
               ${WRONG_ABI})
expect_refused("throwing factory"
               "its rules factory threw: this game needs a scene named 'arena', not '"
               ${THROWING_FACTORY})
expect_refused("null factory" "its rules factory made no rules" ${NULL_FACTORY})
