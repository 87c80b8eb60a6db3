// The InstallAndFindPackage test's judge: the quadra CLI's EXR (R, G, B, A,
// Z as floats) against the consumer's raw pixels and depths, bit for bit.
//   read_reference REF.exr CONSUMER.raw
// And, for the Python test's AOVs, the named channels' values as the file
// stores them (4-byte FLOAT or UINT), interleaved per pixel, row 0 first:
//   read_reference --channels REF.exr OUT.raw NAME...
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

namespace {

int dumpChannels(const char* path, const char* outPath, const std::vector<const char*>& names) {
  Imf::InputFile file(path);
  const Imath::Box2i window = file.header().dataWindow();
  const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
  const std::size_t stride = names.size() * 4;
  std::vector<char> values(std::size_t(width) * height * stride);
  Imf::FrameBuffer buffer;
  for (std::size_t c = 0; c < names.size(); ++c) {
    const Imf::Channel* channel = file.header().channels().findChannel(names[c]);
    if (!channel || (channel->type != Imf::FLOAT && channel->type != Imf::UINT))
      return std::fprintf(stderr, "read_reference: %s has no FLOAT or UINT channel %s\n", path,
                          names[c]),
             1;
    buffer.insert(names[c], Imf::Slice(channel->type, values.data() + c * 4, stride,
                                       std::size_t(width) * stride));
  }
  file.setFrameBuffer(buffer);
  file.readPixels(window.min.y, window.max.y);
  std::ofstream out(outPath, std::ios::binary);
  out.write(values.data(), std::streamsize(values.size()));
  return out ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 5 && std::strcmp(argv[1], "--channels") == 0)
    return dumpChannels(argv[2], argv[3], std::vector<const char*>(argv + 4, argv + argc));
  if (argc != 3)
    return std::fprintf(stderr,
                        "usage: read_reference REF.exr CONSUMER.raw\n"
                        "       read_reference --channels REF.exr OUT.raw NAME...\n"),
           1;
  Imf::InputFile file(argv[1]);
  const Imath::Box2i window = file.header().dataWindow();
  const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
  std::vector<float> rgba(std::size_t(width) * height * 4), depth(std::size_t(width) * height);
  Imf::FrameBuffer buffer;
  const char* names[] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c)
    buffer.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgba.data() + c), 16,
                                       std::size_t(width) * 16));
  buffer.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(depth.data()), 4,
                                std::size_t(width) * 4));
  file.setFrameBuffer(buffer);
  file.readPixels(window.min.y, window.max.y);
  std::ifstream in(argv[2], std::ios::binary);
  const std::vector<char> raw((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
  if (raw.size() != (rgba.size() + depth.size()) * 4)
    return std::fprintf(stderr, "read_reference: %zu bytes from the consumer, %dx%d expected\n",
                        raw.size(), width, height),
           1;
  std::size_t differing = 0, covered = 0;
  for (std::size_t i = 0; i < rgba.size(); ++i) {
    differing += std::memcmp(&raw[i * 4], &rgba[i], 4) != 0;
    covered += i % 4 == 3 && rgba[i] > 0.0f;
  }
  for (std::size_t i = 0; i < depth.size(); ++i)
    differing += std::memcmp(&raw[(rgba.size() + i) * 4], &depth[i], 4) != 0;
  std::printf("read_reference: %dx%d, %zu covered pixels, %zu values differ from the CLI's\n",
              width, height, covered, differing);
  return differing == 0 && covered > std::size_t(width) * height / 4 ? 0 : 1;
}
