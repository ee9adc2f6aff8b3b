# The repository describes itself (README.md, docs/): included from tests/CMakeLists.txt.
#   docs.no_outside_references   no tracked file refers to a document outside the repository
#   docs.readme_is_a_front_page  README.md has at most 250 lines
#   docs.links_resolve           every relative link (and anchor) of README.md and docs/*.md resolves
#   docs.keys_md                 docs/keys.md is what `vibromap keys` prints (make_keys_md.cmake)
#   docs.exit_codes              every exit code docs/*.md states agrees with README.md's table
#                                (check_exit_codes.py; needs Python)
#   docs.notebook                docs/notebooks/tour.ipynb runs (nbclient, ipykernel) and every
#                                number it prints is the command line's (check_notebook.py)
# and the same checks on a made-up tree with one fault of each kind, which they must refuse.
set(_vibromap_docs_check ${PROJECT_SOURCE_DIR}/tests/docs/check_docs.cmake)
foreach(_what references readme links)
  add_test(NAME docs.${_what} COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DWHAT=${_what}
           -P ${_vibromap_docs_check})
endforeach()
add_test(NAME docs.keys_md COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:vibromap>
         -DCHECK=${PROJECT_SOURCE_DIR}/docs/keys.md -P ${PROJECT_SOURCE_DIR}/tests/docs/make_keys_md.cmake)

# The made-up tree (outside any git work tree of its own, so the file walk is checked): a
# README of 251 lines with a link to a missing file, a page with an anchor to no heading, and a
# source file naming the brief (the name assembled here, so that this file does not name it).
set(_bad ${CMAKE_CURRENT_BINARY_DIR}/docs_bad_tree)
set(_brief "SPEC")
string(REPEAT "line\n" 250 _lines)
file(WRITE ${_bad}/README.md "# x\n${_lines}[gone](docs/missing.md)\n")
file(WRITE ${_bad}/docs/page.md "# Page\n\n[there](page.md#nowhere) [here](#page)\n")
file(WRITE ${_bad}/src/a.cpp "// see ${_brief}.md\n")
foreach(_what references readme links)
  add_test(NAME docs.${_what}_refuses_a_bad_tree COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${_bad}
           -DWHAT=${_what} -P ${_vibromap_docs_check})
endforeach()
set_tests_properties(docs.references_refuses_a_bad_tree PROPERTIES
  PASS_REGULAR_EXPRESSION "outside the repository.*src/a\\.cpp: // see ")
set_tests_properties(docs.readme_refuses_a_bad_tree PROPERTIES
  PASS_REGULAR_EXPRESSION "README\\.md has 252 lines, more than 250")
set_tests_properties(docs.links_refuses_a_bad_tree PROPERTIES
  PASS_REGULAR_EXPRESSION "README\\.md: link to docs/missing\\.md: no such file.*docs/page\\.md: link to page\\.md#nowhere: no such heading")

# The exit codes: a made-up tree whose page gives a full disk exit 2 and a stop exit 4.
if(VibromapPython_FOUND)
  set(_check_codes ${PROJECT_SOURCE_DIR}/tests/docs/check_exit_codes.py)
  add_test(NAME docs.exit_codes COMMAND "${VibromapPython_EXECUTABLE}" ${_check_codes} ${PROJECT_SOURCE_DIR})
  set(_bad_codes ${CMAKE_CURRENT_BINARY_DIR}/docs_bad_exit_codes)
  file(WRITE ${_bad_codes}/README.md "# x\n\n## Exit codes\n\n| code | meaning |\n|---|---|\n"
       "| 0 | done |\n| 1 | an unexpected error (a bug) |\n| 2 | bad input |\n"
       "| 3 | stopped by SIGINT, SIGTERM or SIGUSR1 |\n"
       "| 4 | a file could not be read or written, or a resource (disk, memory) ran out |\n\n## Next\n")
  file(WRITE ${_bad_codes}/docs/guide-x.md "# X\n\nA map that cannot fit on its disk is refused (exit 2).\n"
       "A run stopped by SIGTERM exits 4. A bad key is refused with exit 2. Done: exit 7.\n")
  add_test(NAME docs.exit_codes_refuses_a_bad_tree COMMAND "${VibromapPython_EXECUTABLE}" ${_check_codes} ${_bad_codes})
  set_tests_properties(docs.exit_codes_refuses_a_bad_tree PROPERTIES
    PASS_REGULAR_EXPRESSION "guide-x\\.md:3: states exit 2 for 'disk'.*guide-x\\.md:4: states exit 4 for 'sigterm'.*guide-x\\.md:4: exit 7 is not in.*3 disagreements")
  unset(_check_codes)
  unset(_bad_codes)
endif()

# The tour notebook, run in a kernel of the interpreter vibromap._core is built for, against
# the built program; skipped (exit 77, the reason in its output) where that interpreter lacks
# nbclient or ipykernel. The made-up notebook has one fault of each kind: an output committed,
# a number one ulp off, a number missing and one unchecked, an unchecked cell, a picture
# missing, a cell that raises.
if(TARGET vibromap_python)
  set(_check_notebook ${PROJECT_SOURCE_DIR}/tests/docs/check_notebook.py)
  set(_notebook_env "PYTHONPATH=${PROJECT_BINARY_DIR}/python;PYTHONDONTWRITEBYTECODE=1;VIBROMAP_EXE=$<TARGET_FILE:vibromap>")
  add_test(NAME docs.notebook COMMAND "${VIBROMAP_PYTHON_EXECUTABLE}" ${_check_notebook}
           ${PROJECT_SOURCE_DIR}/docs/notebooks/tour.ipynb ${PROJECT_SOURCE_DIR})
  add_test(NAME docs.notebook_refuses_a_bad_notebook COMMAND "${VIBROMAP_PYTHON_EXECUTABLE}" ${_check_notebook}
           ${PROJECT_SOURCE_DIR}/tests/docs/wrong_notebook.ipynb ${PROJECT_SOURCE_DIR})
  set_tests_properties(docs.notebook docs.notebook_refuses_a_bad_notebook PROPERTIES
    LABELS "docs;python" TIMEOUT 300 SKIP_RETURN_CODE 77 ENVIRONMENT "${_notebook_env}")
  set_tests_properties(docs.notebook PROPERTIES PROCESSORS 2)  # its map runs on 2 MPI ranks
  set_tests_properties(docs.notebook_refuses_a_bad_notebook PROPERTIES PASS_REGULAR_EXPRESSION
    "'untagged' is committed with outputs.*'point': does not show soft.*'point': shows extra = 1, which no reference covers.*'point': k_con = 8\\.96[0-9]+, the command line's is 8\\.96.*'untagged' shows output that no check covers.*'trajectory' draws no picture.*'boom' failed: ZeroDivisionError.*7 disagreement")
  execute_process(COMMAND "${VIBROMAP_PYTHON_EXECUTABLE}" -c "import nbclient, ipykernel"
                  RESULT_VARIABLE _notebook_rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT _notebook_rc EQUAL 0)
    message(STATUS "docs.notebook will be skipped: ${VIBROMAP_PYTHON_EXECUTABLE} cannot import nbclient "
                   "and ipykernel (Debian: python3-nbclient python3-ipykernel)")
  endif()
  unset(_check_notebook)
  unset(_notebook_env)
  unset(_notebook_rc)
endif()
unset(_bad)
unset(_brief)
unset(_lines)
unset(_vibromap_docs_check)
