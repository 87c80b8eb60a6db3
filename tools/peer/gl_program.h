// What every OpenGL pass of the peer (tools/peer/) needs: GL errors as
// quadra's Error, and shader programs compiled and linked from source, a
// failure's log in one line.
#pragma once

#include <GL/gl.h>

#include <string>

namespace quadra {

// Throws Error("llvmpipe: OpenGL error 0x.... while <what>") when GL has one.
void throwOnGlError(const char* what);

// A program of a vertex and a fragment shader, each `prelude` (the #version
// line and any #defines) followed by its body.
GLuint linkProgram(const std::string& prelude, const char* vertexBody, const char* fragmentBody);

}  // namespace quadra
