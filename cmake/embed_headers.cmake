# SPDX-License-Identifier: BSD-3-Clause
# Turn dynkit's public headers (include/dynkit/*.h) into a C source of byte arrays for the
# jit layer, which writes them into its cache so that models compile against the headers of
# the running dynkit wherever it is installed or run from. Run as a script:
#   cmake -DBASE=<include/dynkit> -DFILES=<names separated by ','> -DOUTPUT=<file.c>
#         -P embed_headers.cmake
# Each header becomes `static const unsigned char` data with a terminating NUL (not counted
# in its size) and one entry of dyn_jit_headers[] (src/jit/jit_internal.h); the SHA-256 of
# the names and contents (dyn_jit_headers_hash) names the cache's include directory.
string(REPLACE "," ";" files "${FILES}")
list(SORT files)
set(body "/* Generated from include/dynkit/ by cmake/embed_headers.cmake at build time: do not edit. */\n")
string(APPEND body "#include \"jit_internal.h\"\n\n")
set(table "")
set(all "")
set(index 0)
foreach(name IN LISTS files)
  file(READ "${BASE}/${name}" text)
  string(APPEND all "${name}\n${text}\n")
  file(READ "${BASE}/${name}" hex HEX)
  string(LENGTH "${hex}" hex_length)
  math(EXPR size "${hex_length} / 2")
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," hex "${hex}")
  string(REGEX REPLACE "((0x[0-9a-f][0-9a-f],){24})" "\\1\n" hex "${hex}")
  string(APPEND body "/* ${name} */\nstatic const unsigned char header_${index}[] = {\n${hex}0x00};\n\n")
  string(APPEND table "    {\"${name}\", header_${index}, ${size}},\n")
  math(EXPR index "${index} + 1")
endforeach()
string(SHA256 hash "${all}")
string(APPEND body "const dyn_jit_header dyn_jit_headers[] = {\n${table}};\n")
string(APPEND body "const int dyn_jit_header_count = ${index};\n")
string(APPEND body "const char dyn_jit_headers_hash[] = \"${hash}\";\n")
# write only when changed, so the layer is not rebuilt for nothing
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
  if(old STREQUAL body)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${body}")
