# What `cmake --install` (make install) puts where (docs/install.md):
#   bin/rescuesim                          the CLI
#   bin/rescuesim-bench                    the benchmarks (`rescuesim bench` runs it)
#   lib/rescuesim/                         the demonstrations' programs (slam_node, route_node, ...:
#                                          generic names, kept out of bin/ as ROS keeps a package's nodes)
#   share/rescuesim/{worlds,examples}      the shipped worlds (with their robots, meshes and licences)
#                                          and examples; the CLI finds them relative to itself
#   share/doc/rescuesim/                   README, LICENSE, docs/
#   <python dir>/rescuesim/                the Python package (RESCUESIM_PYTHON_INSTALL_DIR)
set(RESCUESIM_INSTALL_DATA_DIR ${CMAKE_INSTALL_DATADIR}/rescuesim)

install(TARGETS rescuesim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
# the benchmarks' program beside the CLI, which runs it for `rescuesim bench` (src/bench)
if(TARGET rescuesim-bench)
  install(TARGETS rescuesim-bench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
endif()
# the CLI (and rescuesim-bench) look for their data relative to themselves first, then in the
# source tree when they run from this build folder, then at the prefix it was configured for
# (app/data_dir.cpp, in rs_app_support)
target_compile_definitions(rs_app_support PRIVATE
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
# /usr/local/lib/python3.X/dist-packages. The folder is chosen when installing, from the prefix
# of that install (make install PREFIX=..., or /usr for the Debian package), so one build serves
# both: lib/python3/dist-packages under a .../usr prefix, lib/python3.X/dist-packages elsewhere
# (then PYTHONPATH=<prefix>/lib/python3.X/dist-packages); RESCUESIM_PYTHON_INSTALL_DIR fixes it.
if(RESCUESIM_PYTHON_BUILT)
  execute_process(COMMAND ${RESCUESIM_PYTHON_EXECUTABLE} -c "import sys; print(f'{sys.version_info[0]}.{sys.version_info[1]}')"
                  OUTPUT_VARIABLE python_xy OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(RESCUESIM_PYTHON_INSTALL_DIR "" CACHE STRING "where the Python package goes, relative to the prefix (empty: chosen by prefix)")
  file(GLOB py_sources ${RESCUESIM_SOURCE_DIR}/python/rescuesim/*.py)
  install(CODE "
    if(NOT \"${RESCUESIM_PYTHON_INSTALL_DIR}\" STREQUAL \"\")
      set(rescuesim_py_dir \"${RESCUESIM_PYTHON_INSTALL_DIR}\")
    elseif(CMAKE_INSTALL_PREFIX MATCHES \"/usr/?$\")
      set(rescuesim_py_dir lib/python3/dist-packages)
    else()
      set(rescuesim_py_dir lib/python${python_xy}/dist-packages)
    endif()
    file(INSTALL ${py_sources} \"$<TARGET_FILE:_rescuesim>\" DESTINATION \"\${CMAKE_INSTALL_PREFIX}/\${rescuesim_py_dir}/rescuesim\")
  " COMPONENT runtime)
endif()

# make deb: a Debian package of the same install with the prefix /usr; its Depends line is
# computed by dpkg-shlibdeps from the libraries the programs link, not listed by hand
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME rescuesim)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_CONTACT "rescuesim developers <rescuesim@users.noreply.github.com>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# beside what dpkg-shlibdeps finds: what is loaded at run time rather than linked. libepoxy
# dlopens libEGL (libglvnd), which loads Mesa's EGL vendor and its software rasteriser for the
# headless cameras; the Python package needs python3 and numpy
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-numpy, libegl1, libegl-mesa0, libgl1-mesa-dri")
set(CPACK_PACKAGE_DESCRIPTION "Bullet physics, worlds drawn as SVG or generated as random mazes, URDF robots and
Gazebo SDF worlds, laser, sonar, cameras (headless EGL), ROS 1 and ROS 2 without a
bridge process, Foxglove and MCAP, rescue missions with a radio model and a referee,
batches and a Python API.")
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://github.com/rescuesim/rescuesim")
set(CPACK_RESOURCE_FILE_LICENSE ${RESCUESIM_SOURCE_DIR}/LICENSE)
include(CPack)
