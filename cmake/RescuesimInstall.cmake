# What `cmake --install` (make install) puts where (docs/install.md):
#   bin/rescuesim                          the CLI
#   lib/rescuesim/                         the demonstrations' programs (slam_node, route_node, ...:
#                                          generic names, kept out of bin/ as ROS keeps a package's nodes)
#   share/rescuesim/{worlds,examples}      the shipped worlds (with their robots, meshes and licences)
#                                          and examples; the CLI finds them relative to itself
#   share/doc/rescuesim/                   README, LICENSE, docs/
#   <python dir>/rescuesim/                the Python package (RESCUESIM_PYTHON_INSTALL_DIR)
set(RESCUESIM_INSTALL_DATA_DIR ${CMAKE_INSTALL_DATADIR}/rescuesim)

install(TARGETS rescuesim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
# the CLI looks for its data relative to itself first, then in the source tree when it runs from
# this build folder, then at the prefix it was configured for
target_compile_definitions(rescuesim PRIVATE
  RESCUESIM_SOURCE_DATA_DIR="${RESCUESIM_SOURCE_DIR}"
  RESCUESIM_BUILD_DIR="${CMAKE_BINARY_DIR}"
  RESCUESIM_INSTALL_DATA_DIR="${CMAKE_INSTALL_FULL_DATADIR}/rescuesim")

foreach(program slam_eval slam_node route_node slam_recorder rescuesim_nav rescuesim_nav_plot)
  if(TARGET ${program})
    install(TARGETS ${program} RUNTIME DESTINATION ${CMAKE_INSTALL_LIBDIR}/rescuesim COMPONENT runtime)
  endif()
endforeach()

install(DIRECTORY ${RESCUESIM_SOURCE_DIR}/worlds ${RESCUESIM_SOURCE_DIR}/examples
        DESTINATION ${RESCUESIM_INSTALL_DATA_DIR} COMPONENT runtime
        PATTERN "CMakeLists.txt" EXCLUDE PATTERN "*.cpp" EXCLUDE PATTERN "*.h" EXCLUDE)
install(FILES ${RESCUESIM_SOURCE_DIR}/README.md ${RESCUESIM_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)
install(DIRECTORY ${RESCUESIM_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)

# the Python package: Debian's python3 reads /usr/lib/python3/dist-packages and
# /usr/local/lib/python3.X/dist-packages; elsewhere set PYTHONPATH to <prefix>/<this>
if(RESCUESIM_PYTHON_BUILT)
  if(CMAKE_INSTALL_PREFIX STREQUAL "/usr")
    set(default_python_dir lib/python3/dist-packages)
  else()
    execute_process(COMMAND ${RESCUESIM_PYTHON_EXECUTABLE} -c "import sys; print(f'{sys.version_info[0]}.{sys.version_info[1]}')"
                    OUTPUT_VARIABLE python_xy OUTPUT_STRIP_TRAILING_WHITESPACE)
    set(default_python_dir lib/python${python_xy}/dist-packages)
  endif()
  set(RESCUESIM_PYTHON_INSTALL_DIR ${default_python_dir} CACHE STRING "where the Python package goes, relative to the prefix")
  install(TARGETS _rescuesim LIBRARY DESTINATION ${RESCUESIM_PYTHON_INSTALL_DIR}/rescuesim COMPONENT runtime)
  file(GLOB py_sources ${RESCUESIM_SOURCE_DIR}/python/rescuesim/*.py)
  install(FILES ${py_sources} DESTINATION ${RESCUESIM_PYTHON_INSTALL_DIR}/rescuesim COMPONENT runtime)
endif()
