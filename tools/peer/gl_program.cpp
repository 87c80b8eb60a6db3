// Compiling and linking the peer's GLSL (see gl_program.h).
#define GL_GLEXT_PROTOTYPES 1
#include "gl_program.h"

#include <GL/glext.h>

#include <algorithm>
#include <cstdio>

#include "core/error.h"

namespace quadra {

void throwOnGlError(const char* what) {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", unsigned(error));
  throw Error(std::string("llvmpipe: OpenGL error ") + code + " while " + what);
}

namespace {

std::string oneLine(const char* log) {
  std::string line(log);
  std::replace(line.begin(), line.end(), '\n', ' ');
  return line;
}

GLuint compileShader(GLenum stage, const std::string& prelude, const char* body) {
  const std::string source = prelude + body;
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[512] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw Error("llvmpipe: shader does not compile: " + oneLine(log));
  }
  return shader;
}

}  // namespace

GLuint linkProgram(const std::string& prelude, const char* vertexBody, const char* fragmentBody) {
  const GLuint vertex = compileShader(GL_VERTEX_SHADER, prelude, vertexBody);
  const GLuint fragment = compileShader(GL_FRAGMENT_SHADER, prelude, fragmentBody);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[512] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw Error("llvmpipe: shader program does not link: " + oneLine(log));
  }
  return program;
}

}  // namespace quadra
