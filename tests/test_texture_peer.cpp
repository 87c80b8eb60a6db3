// `quadra report textures` and its OpenImageIO module (quadra_oiio_peer.so,
// loaded with dlopen): the report's OIIO rows come through the module, the
// report says in one line when there is no usable module and prints
// quadra's rows alone, and the module's C table (tools/peer/texture_peer_abi.h)
// does what it promises. That quadra itself never links OpenImageIO is the
// ctest QuadraLinksNoPeerLibraries (tests/check_linked_libraries.sh).
#include <gtest/gtest.h>

#include <dlfcn.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.h"
#include "peer/texture_peer_abi.h"

namespace quadra {
namespace {

// The smallest report (~4 s on the 2-core machine, the ground truth most of it).
const std::string kSmallReport = "report textures --size 8 --lookups 36 --threads 2";

std::string reportDir(const std::string& name) {
  const fs::path dir = testDir() / name;
  fs::remove_all(dir);
  return dir.string();
}

std::vector<std::string> linesStartingWith(const std::string& text, const std::string& prefix) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) == 0) lines.push_back(line);
  return lines;
}

// Without a usable module: exit 0, quadra's rows, no OIIO rows, and one
// line that says why.
void expectQuadraRowsAndOneNote(const RunResult& r, const std::string& why) {
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("| trilinear |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| aniso-16 |"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("| oiio-"), std::string::npos) << r.out;
  const std::vector<std::string> notes = linesStartingWith(r.out, "OpenImageIO");
  ASSERT_EQ(notes.size(), 1u) << r.out;
  EXPECT_EQ(notes[0].rfind("OpenImageIO: not measured", 0), 0u) << notes[0];
  EXPECT_NE(notes[0].find(why), std::string::npos) << notes[0];
}

TEST(TexturePeer, ReportWithoutAUsableModuleSaysSoInOneLine) {
  expectQuadraRowsAndOneNote(run(kSmallReport + " --oiio-peer none --out-dir " + reportDir("none")),
                             "--oiio-peer none");
  // Not a shared object: dlopen fails, with the file named.
  const fs::path notElf = tempPath("not-a-module.so");
  std::ofstream(notElf) << "not a shared object\n";
  expectQuadraRowsAndOneNote(
      run(kSmallReport + " --oiio-peer " + notElf.string() + " --out-dir " + reportDir("bad")),
      notElf.string());
  // A real shared object without the entry point (found on the loader's path).
  expectQuadraRowsAndOneNote(
      run(kSmallReport + " --oiio-peer libm.so.6 --out-dir " + reportDir("libm")),
      std::string("no ") + QUADRA_TEXTURE_PEER_ENTRY + " entry point");
}

#if defined(QUADRA_OIIO_PEER_PATH)

// The default place: the module beside quadra in build/bin. LD_DEBUG=files
// shows who loaded OpenImageIO: the module, not quadra.
TEST(TexturePeer, ReportMeasuresOpenImageIOThroughTheModule) {
  const RunResult r = runProgram("LD_DEBUG=files " + std::string(QUADRA_CLI_PATH),
                                 kSmallReport + " --aniso 8 --out-dir " + reportDir("module"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("| oiio-trilinear |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| oiio-aniso-8 |"), std::string::npos) << r.out;
  const std::vector<std::string> notes = linesStartingWith(r.out, "OpenImageIO");
  ASSERT_EQ(notes.size(), 1u) << r.out;
  EXPECT_EQ(notes[0].rfind("OpenImageIO 2.", 0), 0u) << notes[0];
  const std::string peer = fs::path(QUADRA_OIIO_PEER_PATH).filename().string();
  const std::size_t loaded = r.err.find("file=libOpenImageIO.so");
  ASSERT_NE(loaded, std::string::npos) << "OpenImageIO was never loaded";
  const std::string line = r.err.substr(loaded, r.err.find('\n', loaded) - loaded);
  EXPECT_NE(line.find("needed by"), std::string::npos) << line;
  EXPECT_NE(line.find(peer), std::string::npos) << line;
}

// The C table on its own: a constant texture looks up as its colour in both
// modes, the scratch file goes with the texture, and a failure is a message.
TEST(TexturePeer, ModuleTableLooksUpAConstantTexture) {
  void* module = dlopen(QUADRA_OIIO_PEER_PATH, RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(module, nullptr) << dlerror();
  const auto entry =
      reinterpret_cast<QuadraTexturePeerEntry>(dlsym(module, QUADRA_TEXTURE_PEER_ENTRY));
  ASSERT_NE(entry, nullptr);
  const QuadraTexturePeer& peer = *entry();
  EXPECT_EQ(peer.abi, QUADRA_TEXTURE_PEER_ABI);
  EXPECT_STREQ(peer.name, "OpenImageIO");

  const int size = 8;
  const std::array<float, 4> colour = {0.25f, 0.5f, 0.75f, 1.0f};
  std::vector<float> texels;
  for (int i = 0; i < size * size; ++i) texels.insert(texels.end(), colour.begin(), colour.end());
  const fs::path scratch = tempPath("peer-constant.exr");
  std::array<char, 256> error{};
  QuadraPeerTexture* texture =
      peer.create(size, size, texels.data(), scratch.c_str(), 8, error.data(), error.size());
  ASSERT_NE(texture, nullptr) << error.data();
  EXPECT_TRUE(fs::exists(scratch));
  // Magnified, minified past the last level, anisotropic, across the wrap seam.
  const std::vector<float> u = {0.5f, 0.1f, 0.9f, 0.99f}, v = {0.5f, 0.3f, 0.7f, 0.01f},
                           dudx = {0.01f, 2.0f, 0.5f, 0.05f}, dvdx = {0.0f, 0.0f, 0.1f, 0.0f},
                           dudy = {0.0f, 0.0f, 0.0f, 0.0f}, dvdy = {0.01f, 2.0f, 0.02f, 0.05f};
  for (const int mode : {QUADRA_PEER_TRILINEAR, QUADRA_PEER_ANISOTROPIC}) {
    std::vector<float> rgba(u.size() * 4, -1.0f);
    peer.lookup(texture, mode, u.size(), u.data(), v.data(), dudx.data(), dvdx.data(), dudy.data(),
                dvdy.data(), rgba.data());
    for (std::size_t i = 0; i < rgba.size(); ++i)
      EXPECT_NEAR(rgba[i], colour[i % 4], 1e-6) << "mode " << mode << " lookup " << i / 4;
  }
  peer.destroy(texture);
  EXPECT_FALSE(fs::exists(scratch));

  const std::string unwritable = (testDir() / "no-such-folder" / "t.exr").string();
  EXPECT_EQ(
      peer.create(size, size, texels.data(), unwritable.c_str(), 8, error.data(), error.size()),
      nullptr);
  EXPECT_NE(std::string(error.data()).find(unwritable), std::string::npos) << error.data();
  // The module stays loaded, as quadra keeps it (oiio_reference.h).
}

#endif

}  // namespace
}  // namespace quadra
