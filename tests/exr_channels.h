// Test helper: one channel of an EXR file read back with OpenEXR, for tests
// that check what quadra wrote as another program would read it.
#pragma once

#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <cstddef>
#include <filesystem>
#include <type_traits>
#include <vector>

namespace quadra {

// One uint or float channel of an EXR, row-major.
template <class T>
std::vector<T> readChannel(const std::filesystem::path& path, const char* name, int& width,
                           int& height) {
  Imf::InputFile file(path.string().c_str());
  const Imath::Box2i window = file.header().dataWindow();
  width = window.max.x - window.min.x + 1;
  height = window.max.y - window.min.y + 1;
  std::vector<T> values(std::size_t(width) * std::size_t(height));
  Imf::FrameBuffer buffer;
  buffer.insert(name, Imf::Slice(std::is_same_v<T, float> ? Imf::FLOAT : Imf::UINT,
                                 reinterpret_cast<char*>(values.data()), sizeof(T),
                                 sizeof(T) * std::size_t(width)));
  file.setFrameBuffer(buffer);
  file.readPixels(window.min.y, window.max.y);
  return values;
}

}  // namespace quadra
