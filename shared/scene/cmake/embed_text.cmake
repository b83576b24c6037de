# Writes a .cpp defining `const char* const NAMESPACE::SYMBOL` holding the bytes of
# INPUT as a raw string literal. Run with cmake -P at build time, so the output is
# regenerated whenever INPUT changes (the custom command depends on it).
#   cmake -DINPUT=... -DOUTPUT=... -DSYMBOL=... -DNAMESPACE=... -P embed_text.cmake
file(READ "${INPUT}" content)
# -Wpedantic (-Woverlength-strings) warns past 65,536 characters in one literal.
string(LENGTH "${content}" length)
if(length GREATER 60000)
  message(FATAL_ERROR "${INPUT} has ${length} characters; the embedded scene must stay under "
                      "60,000 (use grids)")
endif()
set(delimiter "embedded_text")
string(FIND "${content}" ")${delimiter}\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT} contains the raw string delimiter )${delimiter}\"")
endif()
file(WRITE "${OUTPUT}.tmp"
  "// Generated from ${INPUT} by embed_text.cmake; do not edit.\n"
  "namespace ${NAMESPACE} {\n"
  "extern const char* const ${SYMBOL};\n"
  "const char* const ${SYMBOL} = R\"${delimiter}(${content})${delimiter}\";\n"
  "}\n")
# Only touch the output when it changed, so dependents are not rebuilt needlessly.
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
