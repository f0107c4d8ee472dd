#include "render/gl/egl_context.h"

#include <epoxy/gl.h>

#include <cstring>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"

namespace rescuesim::gl {

namespace {

/// EGL_EXT_device_drm_render_node's query (not in every epoxy's tables).
constexpr EGLint kDrmRenderNodeFile = 0x3377;

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + 1, name)) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

// EGL hands out one display per platform and device, shared by every context on it; the last
// context to go terminates the display
std::mutex g_displays_mutex;
std::map<EGLDisplay, int> g_display_refs;

void acquire_display(EGLDisplay d) {
  const std::lock_guard lock(g_displays_mutex);
  ++g_display_refs[d];
}

void release_display(EGLDisplay d) {
  const std::lock_guard lock(g_displays_mutex);
  if (--g_display_refs[d] <= 0) {
    g_display_refs.erase(d);
    eglTerminate(d);
  }
}

/// An EGL display to try, and how it was found.
struct Candidate {
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string platform;
};

/// Hardware devices with a render node first, then Mesa's surfaceless platform.
std::vector<Candidate> candidate_displays(std::string& problems) {
  std::vector<Candidate> out;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (client == nullptr || !has_extension(client, "EGL_EXT_platform_base")) {
    problems += "libEGL lacks EGL_EXT_platform_base; ";
    return out;
  }
  if (has_extension(client, "EGL_EXT_device_enumeration") && has_extension(client, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (eglQueryDevicesEXT(16, devices, &count) == EGL_TRUE) {
      for (EGLint i = 0; i < count; ++i) {
        const char* ext = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
        if (has_extension(ext, "EGL_MESA_device_software") || !has_extension(ext, "EGL_EXT_device_drm")) continue;
        const char* node =
            has_extension(ext, "EGL_EXT_device_drm_render_node") ? eglQueryDeviceStringEXT(devices[i], kDrmRenderNodeFile) : nullptr;
        if (node == nullptr) continue;
        const EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d != EGL_NO_DISPLAY) out.push_back({d, fmt::format("EGL device {}", node)});
      }
    }
  }
  if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
    const EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) out.push_back({d, "EGL surfaceless"});
    else problems += "Mesa's surfaceless platform gave no display; ";
  } else {
    problems += "libEGL has no EGL_MESA_platform_surfaceless and no hardware device with a render node was found; ";
  }
  return out;
}

/// GL_VERSION of a default context on `d`, to say what the driver offers instead of 4.5 core.
std::string offered_version(EGLDisplay d) {
  const EGLContext c = eglCreateContext(d, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, nullptr);
  if (c == EGL_NO_CONTEXT) return "no OpenGL context at all";
  std::string version = "an unknown version";
  if (eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c) == EGL_TRUE) {
    const auto* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    if (v != nullptr) version = v;
    eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  eglDestroyContext(d, c);
  return version;
}

}  // namespace

EglContext::EglContext() {
  std::string problems;
  std::string offered;
  for (const Candidate& c : candidate_displays(problems)) {
    EGLint major = 0, minor = 0;
    if (eglInitialize(c.display, &major, &minor) != EGL_TRUE) {
      problems += fmt::format("{}: eglInitialize failed (0x{:x}); ", c.platform, eglGetError());
      continue;
    }
    acquire_display(c.display);
    const char* ext = eglQueryString(c.display, EGL_EXTENSIONS);
    if (!has_extension(ext, "EGL_KHR_no_config_context") && !has_extension(ext, "EGL_MESA_configless_context")) {
      problems += fmt::format("{}: no EGL_KHR_no_config_context; ", c.platform);
      release_display(c.display);
      continue;
    }
    if (!has_extension(ext, "EGL_KHR_surfaceless_context")) {
      problems += fmt::format("{}: no EGL_KHR_surfaceless_context; ", c.platform);
      release_display(c.display);
      continue;
    }
    eglBindAPI(EGL_OPENGL_API);
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    const EGLContext context = eglCreateContext(c.display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT) {
      offered += fmt::format("{}{} ({})", offered.empty() ? "" : "; ", offered_version(c.display), c.platform);
      release_display(c.display);
      continue;
    }
    if (eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) != EGL_TRUE) {
      problems += fmt::format("{}: eglMakeCurrent without a surface failed; ", c.platform);
      eglDestroyContext(c.display, context);
      release_display(c.display);
      continue;
    }
    display_ = c.display;
    context_ = context;
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    description_ = fmt::format("{} via {}", renderer != nullptr ? renderer : "unknown renderer", c.platform);
    return;
  }
  if (!offered.empty()) {
    throw Error(SourceRef{"", 0, "Renderer::create_headless"},
                fmt::format("OpenGL 4.5 core is not available: the driver offers {}", offered));
  }
  if (problems.size() >= 2) problems.resize(problems.size() - 2);
  throw Error(SourceRef{"", 0, "Renderer::create_headless"}, fmt::format("no EGL display could be opened: {}", problems));
}

EglContext::EglContext(EglContext&& o) noexcept
    : display_(std::exchange(o.display_, EGL_NO_DISPLAY)),
      context_(std::exchange(o.context_, EGL_NO_CONTEXT)),
      description_(std::move(o.description_)) {}

EglContext::~EglContext() {
  if (context_ == EGL_NO_CONTEXT) return;
  if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  release_display(display_);
}

void EglContext::make_current() const {
  if (eglGetCurrentContext() != context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_);
}

}  // namespace rescuesim::gl
