#pragma once
/// Move-only RAII owners of OpenGL objects (as Magnum's GL wrappers): each holds one name,
/// deletes it on destruction and cannot be copied. They use GL 4.5 direct state access and must
/// be created, used and destroyed with their context current.

#include <epoxy/gl.h>

#include <string>
#include <utility>

#include <Eigen/Core>

namespace rescuesim::gl {

/// Owner of one GL object name; `Traits::destroy(name)` deletes it.
template <class Traits>
class Object {
 public:
  Object() = default;
  explicit Object(GLuint id) : id_(id) {}
  ~Object() { reset(); }
  Object(Object&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Object& operator=(Object&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_ != 0) Traits::destroy(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

struct BufferTraits { static void destroy(GLuint id) { glDeleteBuffers(1, &id); } };
struct VertexArrayTraits { static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); } };
struct TextureTraits { static void destroy(GLuint id) { glDeleteTextures(1, &id); } };
struct RenderbufferTraits { static void destroy(GLuint id) { glDeleteRenderbuffers(1, &id); } };
struct FramebufferTraits { static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); } };
struct ShaderTraits { static void destroy(GLuint id) { glDeleteShader(id); } };
struct ProgramTraits { static void destroy(GLuint id) { glDeleteProgram(id); } };

/// A buffer with immutable storage of `bytes` bytes, filled from `data` (may be null).
class Buffer : public Object<BufferTraits> {
 public:
  Buffer() = default;
  Buffer(std::size_t bytes, const void* data, GLbitfield flags = 0);
};

/// A vertex array object.
class VertexArray : public Object<VertexArrayTraits> {
 public:
  static VertexArray create();
};

/// A 2D texture (single- or multi-sample) with immutable storage.
class Texture : public Object<TextureTraits> {
 public:
  Texture() = default;
  explicit Texture(GLuint id) : Object(id) {}
  /// One level of `internal_format`, `width` × `height` texels; nearest filtering, clamped to edge.
  static Texture create_2d(GLenum internal_format, int width, int height);
};

/// A renderbuffer, multisampled when `samples` > 0.
class Renderbuffer : public Object<RenderbufferTraits> {
 public:
  Renderbuffer() = default;
  static Renderbuffer create(GLenum internal_format, int width, int height, int samples = 0);
};

/// A framebuffer object.
class Framebuffer : public Object<FramebufferTraits> {
 public:
  Framebuffer() = default;
  static Framebuffer create();
  /// Throws Error naming `what` and the status when the attachments do not make a complete framebuffer.
  void check_complete(const char* what) const;
};

/// A compiled shader stage; throws Error with the compiler log when it does not compile.
class Shader : public Object<ShaderTraits> {
 public:
  Shader(GLenum stage, const char* name, const std::string& source);
};

/// A linked program; throws Error with the log when a stage fails or linking fails. Uniform
/// setters look names up each call (programs here have few uniforms, set once per draw or pass);
/// unknown names are ignored, as GL does with location −1.
class Program : public Object<ProgramTraits> {
 public:
  Program() = default;
  Program(const char* name, const std::string& vertex_source, const std::string& fragment_source);

  GLint uniform(const char* name) const { return glGetUniformLocation(id(), name); }
  void set(const char* name, int v) const { glProgramUniform1i(id(), uniform(name), v); }
  void set(const char* name, float v) const { glProgramUniform1f(id(), uniform(name), v); }
  void set(const char* name, const Eigen::Vector2f& v) const { glProgramUniform2fv(id(), uniform(name), 1, v.data()); }
  void set(const char* name, const Eigen::Vector3f& v) const { glProgramUniform3fv(id(), uniform(name), 1, v.data()); }
  void set(const char* name, const Eigen::Matrix4f& m) const { glProgramUniformMatrix4fv(id(), uniform(name), 1, GL_FALSE, m.data()); }
  void set(const char* name, const Eigen::Matrix3f& m) const { glProgramUniformMatrix3fv(id(), uniform(name), 1, GL_FALSE, m.data()); }
};

}  // namespace rescuesim::gl
