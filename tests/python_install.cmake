# SPDX-License-Identifier: BSD-3-Clause
# `cmake --install BUILD --component python --prefix DEST`, then the installed package imported alone (PYTHONPATH
# = its install directory): it must be the installed copy, with the build's version, and run a scene.
# -D: BUILD (build dir), DEST (a scratch prefix, emptied first), PYTHON (interpreter), SUBDIR (IMCOL_PYTHON_INSTALL_DIR),
# VERSION (the project's).
file(REMOVE_RECURSE ${DEST})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --component python --prefix ${DEST} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
if(IS_ABSOLUTE "${SUBDIR}")
  message(FATAL_ERROR "IMCOL_PYTHON_INSTALL_DIR is absolute (${SUBDIR}): --prefix cannot redirect it")
endif()
set(site ${DEST}/${SUBDIR})
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${site} PYTHONDONTWRITEBYTECODE=1
          ${PYTHON} -c "import imcol, pathlib, sys; p = pathlib.Path(imcol.__file__).resolve(); assert p.parent == pathlib.Path(sys.argv[1]).resolve() / 'imcol', p; r = imcol.run(imcol.Scene.load('default'), record='kinematics'); assert r.e is not None and r.solver.steps > 0; print(imcol.__version__)" ${site}
  WORKING_DIRECTORY ${DEST}
  OUTPUT_VARIABLE version OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed package did not import and run (${rc})")
endif()
if(NOT version STREQUAL VERSION)
  message(FATAL_ERROR "installed imcol.__version__ is '${version}', the build's is '${VERSION}'")
endif()
message(STATUS "installed into ${site}: imcol ${version}")
