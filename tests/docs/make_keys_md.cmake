# docs/keys.md from `vibromap keys`: the scene-key reference as Markdown tables.
#
#   cmake -DEXE=build/vibromap -DOUT=docs/keys.md -P tests/docs/make_keys_md.cmake     write it
#   cmake -DEXE=build/vibromap -DCHECK=docs/keys.md -P tests/docs/make_keys_md.cmake   compare (ctest)
#
# `vibromap keys` prints one table per section kind, its columns padded to the header's
# (key, default, unit, allowed, meaning); each row is cut at the header's column starts.
if(NOT DEFINED EXE)
  message(FATAL_ERROR "give -DEXE=path/to/vibromap")
endif()
execute_process(COMMAND "${EXE}" keys RESULT_VARIABLE rc OUTPUT_VARIABLE text ERROR_VARIABLE err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "${EXE} keys failed (exit ${rc}): ${err}")
endif()

# CMake lists split on ';' and group on '[' ']': while the text is a list of lines they are
# held by control characters of the same length, so the columns stay where they are.
string(ASCII 1 SEMICOLON)
string(ASCII 2 LBRACKET)
string(ASCII 3 RBRACKET)
string(REPLACE ";" "${SEMICOLON}" text "${text}")
string(REPLACE "[" "${LBRACKET}" text "${text}")
string(REPLACE "]" "${RBRACKET}" text "${text}")
string(REPLACE "\n" ";" lines "${text}")

function(restore out value)
  string(REPLACE "${SEMICOLON}" ";" value "${value}")
  string(REPLACE "${LBRACKET}" "[" value "${value}")
  string(REPLACE "${RBRACKET}" "]" value "${value}")
  set(${out} "${value}" PARENT_SCOPE)
endfunction()

# One cell: trimmed; a pipe escaped (GFM tables), and in plain text '*' too (emphasis).
function(cell out line begin end code)
  if(end LESS 0)
    string(SUBSTRING "${line}" ${begin} -1 value)
  else()
    math(EXPR length "${end} - ${begin}")
    string(SUBSTRING "${line}" ${begin} ${length} value)
  endif()
  string(STRIP "${value}" value)
  restore(value "${value}")
  string(REPLACE "|" "\\|" value "${value}")
  if(value STREQUAL "")
    set(value " ")
  elseif(code)
    set(value "`${value}`")
  else()
    string(REPLACE "*" "\\*" value "${value}")
  endif()
  set(${out} "${value}" PARENT_SCOPE)
endfunction()

set(md "# Scene keys\n\n")
string(APPEND md "Generated from `vibromap keys` by `tests/docs/make_keys_md.cmake`: do not edit it by hand.\n"
                 "After a change of any scene key, write it again from the repository's top folder with\n\n"
                 "    cmake -DEXE=build/vibromap -DOUT=docs/keys.md -P tests/docs/make_keys_md.cmake\n\n"
                 "(the test `docs.keys_md` fails until it matches the build). The same keys as a scene file, each\n"
                 "with its default and a comment: `vibromap keys --toml`, which is `jobs/reference.toml`.\n"
                 "How scenes are written and read: [guide-run.md](guide-run.md#scenes).\n\n"
                 "## The point: [system], [contact], [forcing], [solver], [analysis], [initial]\n\n")
set(in_table FALSE)
foreach(line IN LISTS lines)
  if(line MATCHES "^key +default +unit +allowed +meaning")
    string(FIND "${line}" "default" c1)
    string(FIND "${line}" "unit" c2)
    string(FIND "${line}" "allowed" c3)
    string(FIND "${line}" "meaning" c4)
    string(APPEND md "| key | default | unit | allowed | meaning |\n|---|---|---|---|---|\n")
    set(in_table TRUE)
  elseif(line STREQUAL "")
    if(in_table)
      string(APPEND md "\n")
    endif()
    set(in_table FALSE)
  elseif(in_table)
    cell(key "${line}" 0 ${c1} TRUE)
    cell(default "${line}" ${c1} ${c2} TRUE)
    cell(unit "${line}" ${c2} ${c3} FALSE)
    cell(allowed "${line}" ${c3} ${c4} FALSE)
    cell(meaning "${line}" ${c4} -1 FALSE)
    string(APPEND md "| ${key} | ${default} | ${unit} | ${allowed} | ${meaning} |\n")
  elseif(line MATCHES "^${LBRACKET}([a-z]+)${RBRACKET} *(.*)$")
    restore(rest "${CMAKE_MATCH_2}")
    string(APPEND md "## [${CMAKE_MATCH_1}]\n\n${rest}\n\n")
  else()
    restore(prose "${line}")
    string(APPEND md "${prose}\n")
  endif()
endforeach()
string(REGEX REPLACE "\n+$" "\n" md "${md}")

if(DEFINED CHECK)
  file(READ "${CHECK}" have)
  if(NOT have STREQUAL md)
    message(FATAL_ERROR "${CHECK} is not what `vibromap keys` prints now: write it again with\n"
                        "  cmake -DEXE=build/vibromap -DOUT=docs/keys.md -P tests/docs/make_keys_md.cmake")
  endif()
elseif(DEFINED OUT)
  file(WRITE "${OUT}" "${md}")
else()
  message(FATAL_ERROR "give -DOUT=docs/keys.md (write) or -DCHECK=docs/keys.md (compare)")
endif()
