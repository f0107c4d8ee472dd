// The viewer's window: GLFW for the window and input, an OpenGL 3.3 core context (through
// epoxy, like the rest of render/gl), and Dear ImGui's GLFW + OpenGL 3 backends for the panels.

#include "render/gl/viewer_window.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "render/gl/gl_objects.h"

namespace rescuesim {

namespace gl {

namespace {

/// GLFW reports failures through a callback; the last message explains the next failed call.
std::string g_glfw_error;
void on_glfw_error(int code, const char* description) { g_glfw_error = fmt::format("{} (GLFW error 0x{:x})", description, code); }

/// GLFW and ImGui keep global state: one window at a time.
std::atomic<bool> g_window_open{false};

int glfw_key(ViewerKey k) {
  switch (k) {
    case ViewerKey::up: return GLFW_KEY_UP;
    case ViewerKey::down: return GLFW_KEY_DOWN;
    case ViewerKey::left: return GLFW_KEY_LEFT;
    case ViewerKey::right: return GLFW_KEY_RIGHT;
    case ViewerKey::w: return GLFW_KEY_W;
    case ViewerKey::a: return GLFW_KEY_A;
    case ViewerKey::s: return GLFW_KEY_S;
    case ViewerKey::d: return GLFW_KEY_D;
    case ViewerKey::i: return GLFW_KEY_I;
    case ViewerKey::k: return GLFW_KEY_K;
    case ViewerKey::j: return GLFW_KEY_J;
    case ViewerKey::l: return GLFW_KEY_L;
    case ViewerKey::f: return GLFW_KEY_F;
    case ViewerKey::space: return GLFW_KEY_SPACE;
    case ViewerKey::escape: return GLFW_KEY_ESCAPE;
    case ViewerKey::shift: return GLFW_KEY_LEFT_SHIFT;
  }
  return GLFW_KEY_UNKNOWN;
}

class GlfwViewerWindow final : public ViewerWindow {
 public:
  explicit GlfwViewerWindow(const ViewerWindowOptions& o) {
    if (g_window_open.exchange(true)) throw Error(SourceRef{"", 0, "ViewerWindow::open"}, "a viewer window is already open");
    glfwSetErrorCallback(on_glfw_error);
    if (glfwInit() != GLFW_TRUE) {
      g_window_open = false;
      throw Error(SourceRef{"", 0, "ViewerWindow::open"},
                  fmt::format("no display: {}", g_glfw_error.empty() ? "GLFW could not start" : g_glfw_error));
    }
    // a core 3.3 context is what ImGui's OpenGL 3 backend and every platform (macOS too) offer
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(o.width, o.height, o.title.c_str(), nullptr, nullptr);
    if (window_ == nullptr) {
      glfwTerminate();
      g_window_open = false;
      throw Error(SourceRef{"", 0, "ViewerWindow::open"}, fmt::format("no OpenGL 3.3 window could be created: {}", g_glfw_error));
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(o.vsync ? 1 : 0);

    // our scroll callback goes first, so ImGui's backend chains to it
    glfwSetWindowUserPointer(window_, this);
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
      static_cast<GlfwViewerWindow*>(glfwGetWindowUserPointer(w))->pending_scroll_ += dy;
    });
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // the layout is the viewer's, not a file in the working folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
  }

  ~GlfwViewerWindow() override {
    glfwMakeContextCurrent(window_);
    textures_.clear();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
    g_window_open = false;
  }

  void poll(double wait_seconds) override {
    pending_scroll_ = 0;
    if (wait_seconds > 0) glfwWaitEventsTimeout(wait_seconds);
    else glfwPollEvents();
    scroll_ = pending_scroll_;
  }

  bool should_close() const override { return glfwWindowShouldClose(window_) == GLFW_TRUE; }

  int width() const override {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    return w;
  }
  int height() const override {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    return h;
  }

  bool key_down(ViewerKey key) const override {
    if (ImGui::GetIO().WantTextInput) return false;
    if (key == ViewerKey::shift) {
      return glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(window_, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    }
    return glfwGetKey(window_, glfw_key(key)) == GLFW_PRESS;
  }

  ViewerMouse mouse() const override {
    ViewerMouse m;
    glfwGetCursorPos(window_, &m.x, &m.y);
    m.left = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    m.middle = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    m.right = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    m.scroll = scroll_;
    m.over_ui = ImGui::GetIO().WantCaptureMouse;
    return m;
  }

  void upload(const std::string& name, int width, int height, const std::uint8_t* rgb) override {
    if (width <= 0 || height <= 0 || rgb == nullptr) return;
    Tex& t = textures_[name];
    if (!t.texture) {
      GLuint id = 0;
      glGenTextures(1, &id);
      t.texture = Object<TextureTraits>(id);
    }
    glBindTexture(GL_TEXTURE_2D, t.texture.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (t.width != width || t.height != height) {
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, width, height, 0, GL_RGB, GL_UNSIGNED_BYTE, rgb);
      t.width = width;
      t.height = height;
    } else {
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb);
    }
    // mipmaps: panels show camera images smaller than they are, and should not shimmer
    glGenerateMipmap(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, 0);
  }

  void* texture(const std::string& name) const override {
    const auto it = textures_.find(name);
    if (it == textures_.end() || !it->second.texture) return nullptr;
    return reinterpret_cast<void*>(static_cast<std::uintptr_t>(it->second.texture.id()));
  }

  void frame(const std::function<void()>& ui, ColorImage* capture) override {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (ui) ui();
    ImGui::Render();

    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    glViewport(0, 0, w, h);
    glClearColor(0.10f, 0.11f, 0.13f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    // the back buffer holds the finished frame until the swap: read it bottom-up, flip to top-down
    if (capture != nullptr) {
      capture->width = w;
      capture->height = h;
      capture->rgb.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
      std::vector<std::uint8_t> rows(capture->rgb.size());
      glReadBuffer(GL_BACK);
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
      const std::size_t stride = static_cast<std::size_t>(w) * 3;
      for (int y = 0; y < h; ++y) {
        std::memcpy(&capture->rgb[static_cast<std::size_t>(y) * stride], &rows[static_cast<std::size_t>(h - 1 - y) * stride], stride);
      }
    }
    glfwSwapBuffers(window_);
  }

 private:
  struct Tex {
    Object<TextureTraits> texture;
    int width = 0, height = 0;
  };

  GLFWwindow* window_ = nullptr;
  std::map<std::string, Tex> textures_;
  double pending_scroll_ = 0, scroll_ = 0;
};

}  // namespace

std::unique_ptr<ViewerWindow> make_glfw_viewer_window(const ViewerWindowOptions& options) {
  return std::make_unique<GlfwViewerWindow>(options);
}

}  // namespace gl

std::unique_ptr<ViewerWindow> ViewerWindow::open(const ViewerWindowOptions& options) { return gl::make_glfw_viewer_window(options); }

ViewerWindow::~ViewerWindow() = default;

}  // namespace rescuesim
