# SPDX-License-Identifier: BSD-3-Clause
# Turn the page's files (web/) into a C source of byte arrays for the dynkit tool, so the
# tool writes self-contained pages without reading files at run time. Run as a script:
#   cmake -DBASE=<dir of the files> -DFILES=<names separated by ','> -DOUTPUT=<file.c>
#         -P embed_web.cmake
# Each file becomes `static const unsigned char` data with a terminating NUL (not counted
# in its size) and one entry of cli_web_assets[] (cli/pages/web_assets.h), in the order given.
string(REPLACE "," ";" files "${FILES}")
set(body "/* Generated from web/ by cmake/embed_web.cmake at build time: do not edit. */\n")
string(APPEND body "#include \"pages/web_assets.h\"\n\n")
set(table "")
set(index 0)
foreach(name IN LISTS files)
  file(READ "${BASE}/${name}" hex HEX)
  string(LENGTH "${hex}" hex_length)
  math(EXPR size "${hex_length} / 2")
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," hex "${hex}")
  string(REGEX REPLACE "((0x[0-9a-f][0-9a-f],){24})" "\\1\n" hex "${hex}")
  string(APPEND body "/* ${name} */\nstatic const unsigned char asset_${index}[] = {\n${hex}0x00};\n\n")
  string(APPEND table "    {\"${name}\", asset_${index}, ${size}},\n")
  math(EXPR index "${index} + 1")
endforeach()
string(APPEND body "const cli_web_asset cli_web_assets[] = {\n${table}};\n")
string(APPEND body "const int cli_web_asset_count = ${index};\n")
# write only when changed, so the tool is not rebuilt for nothing
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
  if(old STREQUAL body)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${body}")
