# The repository describes itself (README.md, docs/): included from tests/CMakeLists.txt.
#   docs.no_outside_references   no tracked file refers to a document outside the repository
#   docs.readme_is_a_front_page  README.md has at most 250 lines
#   docs.links_resolve           every relative link (and anchor) of README.md and docs/*.md resolves
#   docs.keys_md                 docs/keys.md is what `vibromap keys` prints (make_keys_md.cmake)
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
unset(_bad)
unset(_brief)
unset(_lines)
unset(_vibromap_docs_check)
