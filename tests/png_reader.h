// A PNG's 8-bit RGBA codes as libpng itself reads them, for tests that hold
// quadra's PNG writer (or a byte target that must equal its files) to them.
#pragma once

#include <gtest/gtest.h>
#include <png.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace quadra {

struct Rgba8 {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> bytes;
};

// libpng's own simplified reader; an 8-bit sRGB file comes back code for code.
inline Rgba8 readPngDirectly(const std::string& path) {
  png_image image;
  std::memset(&image, 0, sizeof(image));
  image.version = PNG_IMAGE_VERSION;
  Rgba8 out;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    ADD_FAILURE() << image.message;
    return out;
  }
  EXPECT_EQ(image.format & PNG_FORMAT_FLAG_LINEAR, 0u);
  image.format = PNG_FORMAT_RGBA;
  out.width = int(image.width);
  out.height = int(image.height);
  out.bytes.resize(PNG_IMAGE_SIZE(image));
  EXPECT_TRUE(png_image_finish_read(&image, nullptr, out.bytes.data(), 0, nullptr))
      << image.message;
  return out;
}

}  // namespace quadra
