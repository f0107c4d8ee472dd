#include "render/gl/gl_objects.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/error.h"

namespace rescuesim::gl {

namespace {

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return log.c_str();
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  return log.c_str();
}

}  // namespace

Buffer::Buffer(std::size_t bytes, const void* data, GLbitfield flags) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  Object::operator=(Object(id));
  glNamedBufferStorage(id, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 1)), data, flags);
}

VertexArray VertexArray::create() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  VertexArray v;
  static_cast<Object&>(v) = Object(id);
  return v;
}

Texture Texture::create_2d(GLenum internal_format, int width, int height) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  Texture t;
  static_cast<Object&>(t) = Object(id);
  glTextureStorage2D(id, 1, internal_format, width, height);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

Renderbuffer Renderbuffer::create(GLenum internal_format, int width, int height, int samples) {
  GLuint id = 0;
  glCreateRenderbuffers(1, &id);
  Renderbuffer r;
  static_cast<Object&>(r) = Object(id);
  if (samples > 0) glNamedRenderbufferStorageMultisample(id, samples, internal_format, width, height);
  else glNamedRenderbufferStorage(id, internal_format, width, height);
  return r;
}

Framebuffer Framebuffer::create() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  Framebuffer f;
  static_cast<Object&>(f) = Object(id);
  return f;
}

void Framebuffer::check_complete(const char* what) const {
  const GLenum status = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw Error(SourceRef{"", 0, "gl::Framebuffer"}, fmt::format("the {} framebuffer is incomplete (status 0x{:x})", what, status));
  }
}

Shader::Shader(GLenum stage, const char* name, const std::string& source) {
  Object::operator=(Object(glCreateShader(stage)));
  const char* text = source.c_str();
  glShaderSource(id(), 1, &text, nullptr);
  glCompileShader(id());
  GLint ok = GL_FALSE;
  glGetShaderiv(id(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    throw Error(SourceRef{"", 0, "gl::Shader"}, fmt::format("the {} {} shader does not compile:\n{}", name,
                                                            stage == GL_VERTEX_SHADER ? "vertex" : "fragment", shader_log(id())));
  }
}

Program::Program(const char* name, const std::string& vertex_source, const std::string& fragment_source) {
  const Shader vs(GL_VERTEX_SHADER, name, vertex_source);
  const Shader fs(GL_FRAGMENT_SHADER, name, fragment_source);
  Object::operator=(Object(glCreateProgram()));
  glAttachShader(id(), vs.id());
  glAttachShader(id(), fs.id());
  glLinkProgram(id());
  glDetachShader(id(), vs.id());
  glDetachShader(id(), fs.id());
  GLint ok = GL_FALSE;
  glGetProgramiv(id(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    throw Error(SourceRef{"", 0, "gl::Program"}, fmt::format("the {} program does not link:\n{}", name, program_log(id())));
  }
}

}  // namespace rescuesim::gl
