#[=======================================================================[.rst:
FindVibromapPython
------------------

Finds a Python interpreter that can import the modules of vibromap's ``postprocess/``
(numpy, h5py, matplotlib; pytest for its tests). FindPython3 is not used because the first
``python3`` it sees is often not the one Debian's python3-* packages were installed for (a
pyenv shim, a conda or venv interpreter): what matters is what the interpreter can import.
``postprocess/vibromap-post`` tries the same candidates in the same order at run time.

Candidates, in order: the cache variable ``VIBROMAP_PYTHON`` (if set), ``/usr/bin/python3``,
then ``python3`` and ``python`` on ``PATH``. Each is run as
``<interp> -c "import <modules>"``; the first that succeeds is taken.

Input variables:

``VIBROMAP_PYTHON`` (cache, FILEPATH)
  Interpreter to try first.
``VibromapPython_MODULES``
  Modules to import (default: ``numpy h5py matplotlib pytest``).

Result variables:

``VibromapPython_FOUND``
``VibromapPython_EXECUTABLE``  the interpreter
``VibromapPython_VERSION``     its version, e.g. 3.11.2
``VibromapPython_TRIED``       the candidates tried (for messages)
#]=======================================================================]

set(VIBROMAP_PYTHON "" CACHE FILEPATH
    "Python interpreter for postprocess/ (needs numpy, h5py, matplotlib; pytest for the tests)")
if(NOT VibromapPython_MODULES)
  set(VibromapPython_MODULES numpy h5py matplotlib pytest)
endif()
list(JOIN VibromapPython_MODULES ", " _vibromap_python_imports)

set(_vibromap_python_candidates)
if(VIBROMAP_PYTHON)
  list(APPEND _vibromap_python_candidates "${VIBROMAP_PYTHON}")
endif()
list(APPEND _vibromap_python_candidates /usr/bin/python3)
foreach(_name IN ITEMS python3 python)
  # Searched afresh on every configure: PATH may have changed (find_program caches otherwise).
  unset(_vibromap_python_on_path CACHE)
  find_program(_vibromap_python_on_path NAMES ${_name})
  if(_vibromap_python_on_path)
    list(APPEND _vibromap_python_candidates "${_vibromap_python_on_path}")
  endif()
  unset(_vibromap_python_on_path CACHE)
endforeach()
list(REMOVE_DUPLICATES _vibromap_python_candidates)

set(VibromapPython_EXECUTABLE "")
set(VibromapPython_VERSION "")
set(VibromapPython_TRIED "")
foreach(_candidate IN LISTS _vibromap_python_candidates)
  list(APPEND VibromapPython_TRIED "${_candidate}")
  execute_process(
    COMMAND "${_candidate}" -c "import ${_vibromap_python_imports}; import sys; print('%d.%d.%d' % sys.version_info[:3])"
    RESULT_VARIABLE _vibromap_python_rc
    OUTPUT_VARIABLE _vibromap_python_version
    OUTPUT_STRIP_TRAILING_WHITESPACE
    ERROR_QUIET
    TIMEOUT 60)
  if(_vibromap_python_rc EQUAL 0)
    set(VibromapPython_EXECUTABLE "${_candidate}")
    set(VibromapPython_VERSION "${_vibromap_python_version}")
    break()
  endif()
  if(VIBROMAP_PYTHON AND _candidate STREQUAL VIBROMAP_PYTHON)
    message(WARNING "VIBROMAP_PYTHON=${VIBROMAP_PYTHON} cannot import ${_vibromap_python_imports}; trying others")
  endif()
endforeach()
list(JOIN VibromapPython_TRIED ", " VibromapPython_TRIED)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(VibromapPython
  REQUIRED_VARS VibromapPython_EXECUTABLE
  VERSION_VAR VibromapPython_VERSION
  REASON_FAILURE_MESSAGE "none of ${VibromapPython_TRIED} can import ${_vibromap_python_imports}")

unset(_name)
unset(_candidate)
unset(_vibromap_python_candidates)
unset(_vibromap_python_imports)
unset(_vibromap_python_rc)
unset(_vibromap_python_version)
