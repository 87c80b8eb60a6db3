// Image files in and out: EXR (linear float, with Z) and PNG (sRGB 8-bit).
// Writers never leave a partial file under the requested name: they write a
// temporary beside it and rename on success.
#pragma once

#include <string>

#include "io/frame.h"
#include "texture/image.h"

namespace quadra {

// EXR with half-free FLOAT channels R, G, B, A (premultiplied linear) and Z.
// Throws Error("<path>: <problem>") on failure.
void writeExr(const Frame& frame, const std::string& path);
// PNG, 8-bit sRGB RGBA (colour un-premultiplied before encoding).
void writePng(const Frame& frame, const std::string& path);
// Chooses the writer from the extension (.exr or .png, any case).
void writeFrame(const Frame& frame, const std::string& path);

// Reads a PNG (decoded from sRGB to linear; alpha stays linear) or an EXR
// (already linear; missing channels: RGB 0, A 1) into linear float RGBA.
Image readImage(const std::string& path);

}  // namespace quadra
