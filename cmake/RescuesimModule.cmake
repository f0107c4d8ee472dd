# rescuesim_module(NAME <name> [DIR <folder under src>] [DIRS <subdirs>...] DEPS <targets>...)
# One folder = one static library `rs_<name>`, sources globbed from src/<name> (or src/<DIR>,
# e.g. bridges/ros1) and the listed subfolders. Includes are rooted at src/, so code writes
# #include "core/rng.h".
function(rescuesim_module)
  cmake_parse_arguments(M "" "NAME;DIR" "DIRS;DEPS;PRIVATE_DEPS" ${ARGN})
  if(NOT M_DIR)
    set(M_DIR ${M_NAME})
  endif()
  set(dir ${RESCUESIM_SOURCE_DIR}/src/${M_DIR})
  file(GLOB sources CONFIGURE_DEPENDS ${dir}/*.cpp)
  foreach(sub ${M_DIRS})
    file(GLOB more CONFIGURE_DEPENDS ${dir}/${sub}/*.cpp)
    list(APPEND sources ${more})
  endforeach()
  add_library(rs_${M_NAME} STATIC ${sources})
  target_include_directories(rs_${M_NAME} PUBLIC ${RESCUESIM_SOURCE_DIR}/src)
  target_link_libraries(rs_${M_NAME} PUBLIC ${M_DEPS} PRIVATE ${M_PRIVATE_DEPS})
endfunction()

# rescuesim_tests(NAME <name> DIRS <test dirs> DEPS <targets>)
# One GoogleTest executable per module, from tests/<dir>/*_test.cpp.
function(rescuesim_tests)
  cmake_parse_arguments(T "" "NAME" "DIRS;DEPS" ${ARGN})
  set(sources)
  foreach(sub ${T_DIRS})
    file(GLOB more CONFIGURE_DEPENDS ${RESCUESIM_SOURCE_DIR}/tests/${sub}/*_test.cpp)
    list(APPEND sources ${more})
  endforeach()
  if(NOT sources)
    return()  # a module whose tests are not written yet
  endif()
  add_executable(${T_NAME}_tests ${sources})
  target_link_libraries(${T_NAME}_tests PRIVATE ${T_DEPS} GTest::gtest_main GTest::gmock)
  target_include_directories(${T_NAME}_tests PRIVATE ${RESCUESIM_SOURCE_DIR}/tests)
  target_compile_definitions(${T_NAME}_tests PRIVATE
    RESCUESIM_SOURCE_DIR="${RESCUESIM_SOURCE_DIR}" RESCUESIM_BINARY_DIR="${CMAKE_BINARY_DIR}")
  gtest_discover_tests(${T_NAME}_tests DISCOVERY_TIMEOUT 60 PROPERTIES LABELS ${T_NAME})
endfunction()
