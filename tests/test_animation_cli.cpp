// `quadra render --sequence` end to end: numbered frames of a moving model,
// a static scene's identical frames, the animation chosen by name or index,
// and every bad input a one-line error that writes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.h"

namespace quadra {
namespace {

constexpr const char* kSmall = " --width 64 --height 48 --threads 2";

RunResult render(const std::string& arguments) {
  return run("render " + arguments);
}

TEST(AnimationCli, SequenceWritesNumberedFramesThatMove) {
  const std::string model = modelPath("AnimatedTriangle");
  if (!fs::exists(model)) GTEST_SKIP() << "no " << model;
  const fs::path dir = emptyFolder("moving");
  // The triangle turns a quarter in its first 0.25 s: at 8 fps, frames 0, 1
  // and 2 are 0, 22.5 and 45 degrees round.
  const RunResult r =
      render(model + kSmall + " --sequence 0:2 --fps 8 --out " + (dir / "tri_####.exr").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(fileNames(dir),
            (std::vector<std::string>{"tri_0000.exr", "tri_0001.exr", "tri_0002.exr"}));
  EXPECT_EQ(lineKeyValues(r.out, "quadra frame_ms ").at("frames"), "3");
  std::vector<Image> frames;
  for (const std::string& name : fileNames(dir)) frames.push_back(readImage((dir / name).string()));
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_NE(frames[0].rgba, frames[1].rgba);
  EXPECT_NE(frames[1].rgba, frames[2].rgba);
  EXPECT_NE(frames[0].rgba, frames[2].rgba);
}

// The skinned and morphed models play too: four numbered frames each, and
// their deformation shows between the first and the last (their poses are
// checked against an independent evaluation in test_skinning.cpp).
TEST(AnimationCli, SkinnedAndMorphedModelsRenderSequences) {
  int models = 0;
  for (const char* name : {"SimpleSkin", "RiggedSimple", "RiggedFigure", "CesiumMan", "SimpleMorph",
                           "AnimatedMorphCube"}) {
    const std::string model = modelPath(name);
    if (!fs::exists(model)) continue;
    ++models;
    const fs::path dir = emptyFolder(std::string("deformed_") + name);
    const RunResult r =
        render(model + kSmall + " --sequence 0:3 --fps 2 --out " + (dir / "f_####.png").string());
    ASSERT_EQ(r.exitCode, 0) << name << ": " << r.err;
    ASSERT_EQ(fileNames(dir),
              (std::vector<std::string>{"f_0000.png", "f_0001.png", "f_0002.png", "f_0003.png"}))
        << name;
    EXPECT_NE(readImage((dir / "f_0000.png").string()).rgba,
              readImage((dir / "f_0003.png").string()).rgba)
        << name;
  }
  if (models == 0) GTEST_SKIP() << "no skinned or morphed models";
}

TEST(AnimationCli, StaticSceneSequenceRepeatsTheStillFrame) {
  const fs::path dir = emptyFolder("static");
  const RunResult still =
      render(std::string("builtin:showcase") + kSmall + " --out " + (dir / "still.png").string());
  ASSERT_EQ(still.exitCode, 0) << still.err;
  const RunResult r = render(std::string("builtin:showcase") + kSmall + " --sequence 9:10 --out " +
                             (dir / "seq_#.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(fileNames(dir), (std::vector<std::string>{"seq_10.png", "seq_9.png", "still.png"}));
  const std::string stillBytes = bytesOf(dir / "still.png");
  EXPECT_EQ(bytesOf(dir / "seq_9.png"), stillBytes);
  EXPECT_EQ(bytesOf(dir / "seq_10.png"), stillBytes);
}

TEST(AnimationCli, AnimationIsChosenByNameOrIndex) {
  const std::string model = modelPath("InterpolationTest");
  if (!fs::exists(model)) GTEST_SKIP() << "no " << model;
  const fs::path dir = emptyFolder("chosen");
  // Frame 12 at 24 fps is 0.5 s: the translation animations have moved.
  for (const auto& [choice, name] :
       {std::pair{"'Linear Translation'", "name_##.exr"}, std::pair{"8", "index_##.exr"},
        std::pair{"0", "other_##.exr"}}) {
    const RunResult r = render(model + kSmall + " --sequence 12:12 --animation " + choice +
                               " --out " + (dir / name).string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
  }
  EXPECT_EQ(bytesOf(dir / "name_12.exr"), bytesOf(dir / "index_12.exr"));
  EXPECT_NE(bytesOf(dir / "name_12.exr"), bytesOf(dir / "other_12.exr"));
}

TEST(AnimationCli, BadSequenceInputIsOneLineAndWritesNothing) {
  const std::string model = modelPath("AnimatedTriangle");
  if (!fs::exists(model)) GTEST_SKIP() << "no " << model;
  const fs::path dir = emptyFolder("bad");
  const std::string out = " --out " + (dir / "f_###.exr").string();
  struct Case {
    std::string arguments, mentions;
    int exitCode;  // 1: the scene lacks it; 2: the command line is wrong in itself
  };
  const Case cases[] = {
      {model + " --sequence 0:2 --animation 1" + out, "no such animation", 1},
      {model + " --sequence 0:2 --animation walk" + out, "'walk': no such animation", 1},
      {"builtin:showcase --sequence 0:2 --animation 0" + out, "no such animation", 1},
      {model + " --sequence 3:1" + out, "reversed", 2},
      {model + " --sequence 3" + out, "FIRST:LAST", 2},
      {model + " --sequence 2:" + out, "FIRST:LAST", 2},
      {model + " --sequence -1:2" + out, "--sequence", 2},
      {model + " --sequence 0:2 --out " + (dir / "f.exr").string(), "no run of '#'", 2},
      {model + " --sequence 0:2 --fps 0" + out, "--fps", 2},
      {model + " --animation 0" + out, "only with --sequence", 2},
      {model + " --fps 30" + out, "only with --sequence", 2},
      {model + " --sequence 0:2 --frames 3" + out, "--frames", 2},
  };
  for (const Case& c : cases) {
    const RunResult r = render(c.arguments + kSmall);
    EXPECT_EQ(r.exitCode, c.exitCode) << c.arguments;
    expectOneLineError(r, c.mentions);
    EXPECT_TRUE(fs::is_empty(dir)) << c.arguments << " wrote a file";
  }
}

}  // namespace
}  // namespace quadra
