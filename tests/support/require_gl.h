#pragma once
// What a GL test does when this machine gives it no OpenGL context: it skips, printing why
// (the renderer's error names the EGL call that failed: eglGetPlatformDisplayEXT, eglInitialize,
// eglCreateContext, eglMakeCurrent), unless RESCUESIM_REQUIRE_GL=1 is set, as `make test` and
// CI set it: then it fails, so a render suite that would have skipped fails the run instead.

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

namespace rescuesim::testing_gl {

/// True when the environment sets RESCUESIM_REQUIRE_GL=1 (a GL test must then have a context).
inline bool gl_required() {
  const char* v = std::getenv("RESCUESIM_REQUIRE_GL");
  return v != nullptr && std::strcmp(v, "1") == 0;
}

}  // namespace rescuesim::testing_gl

/// In a test body: when `have_gl` is false, fails (RESCUESIM_REQUIRE_GL=1) or skips, either way
/// printing `reason`, and returns from the test.
#define RS_GL_OR_SKIP(have_gl, reason)                                                           \
  if (!(have_gl) && ::rescuesim::testing_gl::gl_required())                                      \
    GTEST_FAIL() << "RESCUESIM_REQUIRE_GL=1 but there is no headless OpenGL here: " << (reason); \
  if (!(have_gl)) GTEST_SKIP() << "no headless OpenGL here (set RESCUESIM_REQUIRE_GL=1 to fail instead): " << (reason)
