# `cmake --install BUILD --prefix P`:
#   P/bin                                the programs (cosim finds the others beside it)
#   P/lib/python3.X/dist-packages/cosim  the Python package, with the generated coupling_pb2.py (X: the minor version
#                                        of Debian's /usr/bin/python3, whose path holds /usr/local/lib/python3.X/
#                                        dist-packages and /usr/lib/python3.X/dist-packages: `import cosim` works
#                                        after an install into /usr/local or /usr, a PYTHONPATH elsewhere)
#   P/share/cosim/python                 the scripts (rigid_piston.py, plot_run.py, ...), {python} in scenes
#   P/share/cosim/examples               the scenes of configs/ (meshes included)
#   P/share/doc/cosim                    README.md, docs/ (as in the repository: the links work)
foreach(program cosim coupler fluid_solver solid_solver)
  if(TARGET ${program})
    install(TARGETS ${program} RUNTIME DESTINATION bin)
  endif()
endforeach()
if(TARGET cosim_proto_python)
  execute_process(COMMAND /usr/bin/python3 -c "import sys; print(f'python{sys.version_info[0]}.{sys.version_info[1]}')"
                  OUTPUT_VARIABLE COSIM_PYTHON_DIR OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE py_rc)
  if(NOT py_rc EQUAL 0 OR COSIM_PYTHON_DIR STREQUAL "")
    message(FATAL_ERROR "/usr/bin/python3 does not run: the Python package's install directory needs its version")
  endif()
  set(COSIM_PYTHON_SITE lib/${COSIM_PYTHON_DIR}/dist-packages CACHE INTERNAL "the package's place under the prefix")
  install(DIRECTORY ${CMAKE_BINARY_DIR}/python/cosim DESTINATION ${COSIM_PYTHON_SITE}
          FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
  file(GLOB COSIM_PY_INSTALL_SCRIPTS ${CMAKE_SOURCE_DIR}/python/*.py)
  install(PROGRAMS ${COSIM_PY_INSTALL_SCRIPTS} DESTINATION share/cosim/python)
endif()
install(DIRECTORY ${CMAKE_SOURCE_DIR}/configs/ DESTINATION share/cosim/examples)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs/ DESTINATION share/doc/cosim/docs)
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION share/doc/cosim)
