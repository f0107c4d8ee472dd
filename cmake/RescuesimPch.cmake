# Precompiled headers (RESCUESIM_PCH, on by default): the heavy third-party headers nearly every
# translation unit parses through core/ (Eigen, spdlog and fmt, the standard containers), and
# GoogleTest for the tests, compiled once and reused by every target of the same kind.
#
# Measured on this project (docs/building.md has the numbers): parsing world/world.h costs
# about 2.1 s of CPU, 1.2 s of which is Eigen and spdlog; with the header precompiled a TU pays
# about 0.1 s to load it. A PCH per target would cost ~5.5 s each, eating most of that, so
# there is one PCH per compile mode: GCC refuses a PCH built with -fPIC in a -fPIE compile, so
# libraries (-fPIC) share rs_pch's, test programs (-fPIE) share rs_test_pch's, and the CLI
# (-fPIE, no GoogleTest) has its own. Our own headers stay out: they change too often.
# RESCUESIM_PCH=OFF builds without (the sanitizer build does, so that a missing #include that
# the PCH would hide still fails there).

option(RESCUESIM_PCH "Precompile heavy third-party headers (Eigen, spdlog, GoogleTest)" ON)
# The fuzz build instruments our libraries target by target (fuzz/CMakeLists.txt adds
# -fsanitize=fuzzer-no-link,address to each), so one shared PCH compiled without those flags
# would not load in them: clang refuses a PCH whose sanitizer features differ from the TU's.
if(RESCUESIM_FUZZ AND RESCUESIM_PCH)
  message(STATUS "RESCUESIM_FUZZ=ON: precompiled headers off (the fuzz flags are per target)")
  set(RESCUESIM_PCH OFF CACHE BOOL "Precompile heavy third-party headers (Eigen, spdlog, GoogleTest)" FORCE)
endif()

set(RESCUESIM_PCH_HEADERS
  <algorithm> <array> <atomic> <chrono> <cmath> <cstdint> <cstdio> <cstring> <filesystem>
  <functional> <map> <memory> <mutex> <optional> <string> <string_view> <thread> <utility>
  <variant> <vector>
  <Eigen/Core> <Eigen/Geometry> <fmt/format.h> <spdlog/spdlog.h>)

if(RESCUESIM_PCH)
  # the libraries' PCH (position-independent, as the static libraries are)
  add_library(rs_pch OBJECT ${CMAKE_CURRENT_LIST_DIR}/pch/pch.cpp)
  target_link_libraries(rs_pch PUBLIC Eigen3::Eigen spdlog::spdlog fmt::fmt)
  target_precompile_headers(rs_pch PRIVATE ${RESCUESIM_PCH_HEADERS})
endif()

# rescuesim_use_pch(<target> [LIBRARY|EXECUTABLE|TEST])
function(rescuesim_use_pch target kind)
  if(NOT RESCUESIM_PCH)
    return()
  endif()
  if(kind STREQUAL "LIBRARY")
    target_precompile_headers(${target} REUSE_FROM rs_pch)
  elseif(kind STREQUAL "TEST")
    target_precompile_headers(${target} REUSE_FROM rs_test_pch)
  else()
    target_precompile_headers(${target} PRIVATE ${RESCUESIM_PCH_HEADERS})
  endif()
endfunction()
