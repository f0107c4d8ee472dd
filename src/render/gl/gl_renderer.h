#pragma once
/// The OpenGL 4.5 backend of Renderer (no GL types here: render/renderer.cpp creates it).

#include <memory>

#include "render/renderer.h"

namespace rescuesim::gl {

/// A Renderer on a headless EGL context (see Renderer::create_headless).
std::unique_ptr<Renderer> make_headless_renderer(Quality q);

}  // namespace rescuesim::gl
