// The bare GL baseline of `rescuesim bench`: the least a renderer of this size and triangle count
// can cost on the same kind of context — one draw of a triangle grid with a flat-colour shader,
// depth test on, then an RGB8 read-back.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "render/gl/egl_context.h"
#include "render/gl/gl_objects.h"
#include "render/gl/shaders.h"
#include "render/bench/render_bench.h"

namespace rescuesim {

double bare_gl_frames_per_second(int width, int height, int triangles, double seconds) {
  if (width < 1 || width > 8192 || height < 1 || height > 8192 || triangles < 1) {
    throw Error(SourceRef{"", 0, "bare_gl_frames_per_second"},
                fmt::format("size {}x{} px and {} triangles: need sizes in [1, 8192] and at least one triangle", width, height, triangles));
  }
  const gl::EglContext context;
  double fps = 0;
  {
    // a grid of cells over the whole viewport, two triangles per cell, `triangles` in all
    const int cells = (triangles + 1) / 2;
    const int cols = std::max(1, static_cast<int>(std::ceil(std::sqrt(cells * static_cast<double>(width) / height))));
    const int rows = (cells + cols - 1) / cols;
    std::vector<float> xy;
    xy.reserve(static_cast<std::size_t>(triangles) * 6);
    for (int k = 0; k < triangles; ++k) {
      const int cell = k / 2, i = cell % cols, j = cell / cols;
      const float x0 = -1.0f + 2.0f * i / cols, x1 = -1.0f + 2.0f * (i + 1) / cols;
      const float y0 = -1.0f + 2.0f * j / rows, y1 = -1.0f + 2.0f * (j + 1) / rows;
      if (k % 2 == 0) xy.insert(xy.end(), {x0, y0, x1, y0, x1, y1});
      else xy.insert(xy.end(), {x0, y0, x1, y1, x0, y1});
    }
    const gl::Buffer vbo(xy.size() * sizeof(float), xy.data());
    const gl::VertexArray vao = gl::VertexArray::create();
    glVertexArrayVertexBuffer(vao.id(), 0, vbo.id(), 0, 2 * sizeof(float));
    glEnableVertexArrayAttrib(vao.id(), 0);
    glVertexArrayAttribFormat(vao.id(), 0, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao.id(), 0, 0);
    const gl::Program program("bare", gl::shaders::kBareVertex, gl::shaders::kBareFragment);

    const gl::Framebuffer fbo = gl::Framebuffer::create();
    const gl::Renderbuffer color = gl::Renderbuffer::create(GL_RGBA8, width, height);
    const gl::Renderbuffer depth = gl::Renderbuffer::create(GL_DEPTH_COMPONENT32F, width, height);
    glNamedFramebufferRenderbuffer(fbo.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color.id());
    glNamedFramebufferRenderbuffer(fbo.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
    fbo.check_complete("bare loop");
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glUseProgram(program.id());
    glBindVertexArray(vao.id());
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);

    const auto frame = [&] {
      const float clear[4] = {0.6f, 0.7f, 0.8f, 1.0f}, far = 1.0f;
      glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, clear);
      glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far);
      glDrawArrays(GL_TRIANGLES, 0, 3 * triangles);
      glReadnPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, static_cast<GLsizei>(rgb.size()), rgb.data());
    };
    for (int i = 0; i < 3; ++i) frame();
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    int frames = 0;
    double elapsed = 0;
    do {
      frame();
      ++frames;
      elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
    } while (elapsed < seconds);
    fps = frames / elapsed;
  }
  return fps;
}

}  // namespace rescuesim
