# `cmake --install BUILD --prefix P`:
#   P/bin                                the programs (cosim finds the others beside it)
#   P/lib/python3/dist-packages/cosim    the Python package, with the generated coupling_pb2.py
#   P/share/cosim/python                 the scripts (rigid_piston.py, plot_run.py, ...), {python} in scenes
#   P/share/cosim/examples               the scenes of configs/ (meshes included)
#   P/share/doc/cosim                    README.md, docs/ (as in the repository: the links work)
foreach(program cosim coupler fluid_solver solid_solver)
  if(TARGET ${program})
    install(TARGETS ${program} RUNTIME DESTINATION bin)
  endif()
endforeach()
if(TARGET cosim_proto_python)
  install(DIRECTORY ${CMAKE_BINARY_DIR}/python/cosim DESTINATION lib/python3/dist-packages
          FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
  file(GLOB COSIM_PY_INSTALL_SCRIPTS ${CMAKE_SOURCE_DIR}/python/*.py)
  install(PROGRAMS ${COSIM_PY_INSTALL_SCRIPTS} DESTINATION share/cosim/python)
endif()
install(DIRECTORY ${CMAKE_SOURCE_DIR}/configs/ DESTINATION share/cosim/examples)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs/ DESTINATION share/doc/cosim/docs)
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION share/doc/cosim)
