#pragma once
/// A headless OpenGL 4.5 core context through EGL (as Magnum's WindowlessEglApplication): no
/// window and no default framebuffer — everything renders into framebuffer objects.

#include <epoxy/egl.h>

#include <string>

namespace rescuesim::gl {

/// Owns an EGL display reference and a context; move-only.
class EglContext {
 public:
  /// Opens a hardware EGL device with a DRM render node when one is found
  /// (EGL_PLATFORM_DEVICE_EXT), else Mesa's surfaceless platform, and creates a GL 4.5 core
  /// context without a config or surface. Throws Error saying what is missing.
  EglContext();
  ~EglContext();
  EglContext(EglContext&& o) noexcept;
  EglContext& operator=(EglContext&&) = delete;
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  /// Makes the context current on the calling thread (a no-op when it already is).
  void make_current() const;
  /// GL_RENDERER and the EGL platform, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) via EGL surfaceless".
  const std::string& description() const { return description_; }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string description_;
};

}  // namespace rescuesim::gl
