#pragma once
/// ViewerWindow: an on-screen window hosting Dear ImGui, for the interactive viewer. The
/// interface has no graphics or windowing types; the GLFW + OpenGL 3.3 implementation lives in
/// render/gl. The window shows CPU images: callers upload RGB images into named textures and draw
/// them with ImGui::Image(texture(name), ...) inside the frame callback.
///
/// One thread only: open, poll, upload and draw from the thread that opened the window (its GL
/// context stays current there). Headless renderers (Renderer::create_headless) must live on
/// another thread, because one thread cannot hold a GLX and an EGL context at once.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "render/renderer.h"

namespace rescuesim {

/// Keys the viewer reacts to.
enum class ViewerKey { up, down, left, right, w, a, s, d, i, k, j, l, f, space, escape, shift };

/// Mouse state in window coordinates (x right, y down, origin at the top left).
struct ViewerMouse {
  double x = 0, y = 0;
  bool left = false, middle = false, right = false;  ///< buttons held
  double scroll = 0;   ///< wheel clicks since the previous poll (positive: away from the user)
  bool over_ui = false;       ///< ImGui wants the mouse (it is over a widget or window)
};

/// Settings of a window.
struct ViewerWindowOptions {
  int width = 1280, height = 800;  ///< px
  std::string title = "rescuesim";
  bool vsync = true;               ///< wait for the display's refresh when swapping
};

class ViewerWindow {
 public:
  /// Opens a window with an OpenGL context and Dear ImGui. Throws Error when there is no display
  /// ("no display: …" with the windowing system's reason) or the context cannot be created.
  static std::unique_ptr<ViewerWindow> open(const ViewerWindowOptions& options = {});

  virtual ~ViewerWindow();
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  /// Processes window events; call once per frame before reading input. With `wait_seconds` > 0,
  /// first sleeps until an event arrives or that time passes (for idle frames).
  virtual void poll(double wait_seconds = 0) = 0;
  /// True once the user asked to close the window.
  virtual bool should_close() const = 0;
  /// Window size in screen coordinates: the units of ImGui and of mouse() (the framebuffer is
  /// larger on high-DPI displays).
  virtual int width() const = 0;
  virtual int height() const = 0;

  /// Whether a key is held (false while ImGui has keyboard focus, e.g. in a text field).
  virtual bool key_down(ViewerKey key) const = 0;
  /// The mouse as of the last poll().
  virtual ViewerMouse mouse() const = 0;

  /// Copies an RGB image (3 bytes per pixel, rows top-down) into the texture called `name`,
  /// creating or resizing it as needed; mipmapped, trilinear filtering.
  virtual void upload(const std::string& name, int width, int height, const std::uint8_t* rgb) = 0;
  /// The ImGui texture id (ImTextureID) of a named texture, or null when nothing was uploaded.
  virtual void* texture(const std::string& name) const = 0;

  /// Draws one frame: clears, runs `ui` between ImGui's NewFrame and Render (call ImGui there),
  /// and swaps buffers. With `capture`, also reads the finished frame back at framebuffer
  /// resolution (rows top-down) before the swap.
  virtual void frame(const std::function<void()>& ui, ColorImage* capture = nullptr) = 0;

 protected:
  ViewerWindow() = default;
};

}  // namespace rescuesim
