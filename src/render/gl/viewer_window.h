#pragma once
/// The GLFW + OpenGL 3.3 core + Dear ImGui implementation of ViewerWindow (no GL or GLFW types
/// here: render/viewer_window.h is the interface).

#include <memory>

#include "render/viewer_window.h"

namespace rescuesim::gl {

/// A ViewerWindow on a GLFW window (see ViewerWindow::open).
std::unique_ptr<ViewerWindow> make_glfw_viewer_window(const ViewerWindowOptions& options);

}  // namespace rescuesim::gl
