// The two sequences that need no animated file: `quadra render --orbit N`
// (api/renderer.h orbitCamera) and the built-in animated scene
// builtin:flyover. The orbit is checked against its geometric definition
// (distance and angle about the vertical through the bounds' centre, view 0
// the default framing) and end to end; the flyover's nodes against poses
// worked out here by hand from the keys it was built with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "api/renderer.h"
#include "cli_helpers.h"
#include "lab/scene/builtin_scenes.h"
#include "scene/animation.h"
#include "scene/gltf_loader.h"

namespace quadra {
namespace {

glm::dvec3 positionOf(const glm::mat4& world) {
  return glm::dvec3(glm::vec3(world[3]));
}

// ---- orbit ------------------------------------------------------------------------

TEST(Orbit, TurnsTheDefaultFramingAboutTheVerticalThroughTheCentre) {
  const Scene scene = makeBuiltinScene("showcase");
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  const glm::dvec3 centre = 0.5 * (glm::dvec3(lo) + glm::dvec3(hi));
  const Camera first = defaultCamera(scene);
  const Camera view0 = orbitCamera(scene, 0, 7);
  EXPECT_EQ(std::memcmp(&first.world, &view0.world, sizeof(glm::mat4)), 0);
  const glm::dvec3 start = positionOf(first.world) - centre;
  constexpr int kViews = 12;
  for (int view = 0; view < kViews; ++view) {
    const Camera camera = orbitCamera(scene, view, kViews);
    const glm::dvec3 offset = positionOf(camera.world) - centre;
    // Same height and distance from the axis; turned by 360 x view / N about
    // +Y (right-handed: +Z goes towards +X).
    EXPECT_NEAR(offset.y, start.y, 1e-4) << view;
    EXPECT_NEAR(std::hypot(offset.x, offset.z), std::hypot(start.x, start.z), 1e-4) << view;
    const double turned = std::atan2(offset.x, offset.z) - std::atan2(start.x, start.z);
    const double expected = 2.0 * M_PI * view / kViews;
    EXPECT_NEAR(std::remainder(turned - expected, 2.0 * M_PI), 0.0, 1e-5) << view;
    // Still looking at the centre, with the same lens.
    const glm::dvec3 forward = -glm::dvec3(glm::vec3(camera.world[2]));
    EXPECT_NEAR(glm::dot(glm::normalize(forward), glm::normalize(-offset)), 1.0, 1e-6) << view;
    EXPECT_EQ(camera.yfov, first.yfov);
    EXPECT_EQ(camera.znear, first.znear);
    EXPECT_EQ(camera.zfar, first.zfar);
  }
}

TEST(Orbit, WritesOneFramePerViewAndViewKOfNIsView2KOf2N) {
  const std::string model = modelPath("Box");
  if (!fs::exists(model)) GTEST_SKIP() << "no " << model;
  const fs::path dir = emptyFolder("orbit");
  const std::string size = " --width 64 --height 48 --threads 2";
  ASSERT_EQ(run("render " + model + size + " --out " + (dir / "still.exr").string()).exitCode, 0);
  const RunResult four =
      run("render " + model + size + " --orbit 4 --out " + (dir / "four_#.exr").string());
  ASSERT_EQ(four.exitCode, 0) << four.err;
  EXPECT_EQ(lineKeyValues(four.out, "quadra frame_ms ").at("frames"), "4");
  const RunResult eight =
      run("render " + model + size + " --orbit 8 --out " + (dir / "eight_#.exr").string());
  ASSERT_EQ(eight.exitCode, 0) << eight.err;
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(bytesOf(dir / ("four_" + std::to_string(k) + ".exr")),
              bytesOf(dir / ("eight_" + std::to_string(2 * k) + ".exr")))
        << k;
  }
  // Box has no camera: view 0 is the still's default framing.
  EXPECT_EQ(bytesOf(dir / "four_0.exr"), bytesOf(dir / "still.exr"));
  EXPECT_FALSE(fs::exists(dir / "four_4.exr"));
  // A cube turned 90 degrees looks the same; 45 does not.
  const Image a = readImage((dir / "eight_0.exr").string());
  const Image b = readImage((dir / "eight_1.exr").string());
  EXPECT_NE(a.rgba, b.rgba);
}

TEST(Orbit, ShardsSplitTheViewsAsTheyDoASequence) {
  const fs::path dir = emptyFolder("orbit-shard");
  const RunResult r =
      run("render builtin:showcase --width 32 --height 32 --orbit 5 --shard 1/2 "
          "--out " +
          (dir / "v_#.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(fileNames(dir), (std::vector<std::string>{"v_1.png", "v_3.png"}));
}

TEST(Orbit, BadOrbitInputIsOneLineAndWritesNothing) {
  const fs::path dir = emptyFolder("orbit-bad");
  const std::string out = " --out " + (dir / "f_##.png").string();
  struct Case {
    std::string arguments, mentions;
  };
  const Case cases[] = {
      {"--orbit 0" + out, "--orbit"},
      {"--orbit x" + out, "--orbit"},
      {"--orbit 4 --sequence 0:3" + out, "not with --sequence"},
      {"--orbit 4 --animation 0" + out, "--orbit"},
      {"--orbit 4 --eye 0,0,5" + out, "--eye"},
      {"--orbit 4 --frames 2" + out, "--frames"},
      {"--orbit 4 --out " + (dir / "f.png").string(), "no run of '#'"},
  };
  for (const Case& c : cases) {
    const RunResult r = run("render builtin:showcase --width 32 --height 32 " + c.arguments);
    EXPECT_EQ(r.exitCode, 2) << c.arguments;  // each the command line's fault
    expectOneLineError(r, c.mentions);
    EXPECT_TRUE(fs::is_empty(dir)) << c.arguments << " wrote a file";
  }
}

// ---- the sequence writer ----------------------------------------------------------

// Frames are written on the writer's thread (tools/sequence_writer.h): a write
// that fails there still ends the run with one line and exit status 1, and
// the frames handed over before it are written in order.
TEST(SequenceWriter, AFailedWriteEndsTheSequenceWithOneLine) {
  const fs::path dir = emptyFolder("writer");
  const std::string missing = (dir / "no-such-folder" / "f_#.png").string();
  const RunResult r =
      run("render builtin:flyover --width 32 --height 18 --sequence 0:5 --out " + missing);
  EXPECT_EQ(r.exitCode, 1);
  expectOneLineError(r, "cannot create file");
  EXPECT_TRUE(fs::is_empty(dir));
  const RunResult ordered =
      run("render builtin:flyover --width 32 --height 18 --sequence 3:7 "
          "--out " +
          (dir / "f_#.png").string());
  ASSERT_EQ(ordered.exitCode, 0) << ordered.err;
  std::vector<std::string> written;
  std::istringstream lines(ordered.out);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("quadra wrote ", 0) == 0)
      written.push_back(fs::path(line.substr(13)).filename());
  EXPECT_EQ(written,
            (std::vector<std::string>{"f_3.png", "f_4.png", "f_5.png", "f_6.png", "f_7.png"}));
}

// ---- flyover ----------------------------------------------------------------------

struct Posed {
  Scene scene;
  NodePose pose;
};

Posed flyoverAt(double seconds) {
  Posed posed{makeBuiltinScene("flyover"), {}};
  poseNodes(posed.scene, 0, seconds, posed.pose);
  placeOnNodes(posed.scene, posed.pose);
  return posed;
}

TEST(Flyover, KeyTimeZeroAndTheRestPoseKeepTheBuiltBits) {
  const Scene built = makeBuiltinScene("flyover");
  ASSERT_EQ(built.animations.size(), 1u);
  EXPECT_DOUBLE_EQ(animationDuration(built.animations[0]), 4.0);
  for (const int animation : {-1, 0}) {
    Scene posed = built;
    NodePose pose;
    poseNodes(posed, animation, 0.0, pose);
    placeOnNodes(posed, pose);
    for (std::size_t i = 0; i < built.instances.size(); ++i)
      EXPECT_EQ(
          std::memcmp(&built.instances[i].world, &posed.instances[i].world, sizeof(glm::mat4)), 0)
          << "instance " << i << " animation " << animation;
    EXPECT_EQ(std::memcmp(&built.cameras[0].world, &posed.cameras[0].world, sizeof(glm::mat4)), 0)
        << "animation " << animation;
  }
}

TEST(Flyover, EveryInterpolationMovesItsNodeAsItsKeysSay) {
  // Instances: 0 ground (static), 1 the spinning cube on the turntable,
  // 2 the bouncing ball, 3 the masked panel.
  const Posed start = flyoverAt(0.0);
  // The ball, CUBICSPLINE: key 0 at the ground (y 0.6) leaving at 6.4 units/s
  // (a parabola peaking 0.5 s later), scaled by the 0.5 s interval; key 1 at
  // the top (2.2) with zero tangent. The Hermite basis at u = 1/2:
  // 0.5 p0 + 0.125 m0 + 0.5 p1 - 0.125 m1.
  const double p0 = 0.6, p1 = 2.2, m0 = 2.0 * (p1 - p0) / 0.5 * 0.5;
  EXPECT_NEAR(positionOf(flyoverAt(0.25).scene.instances[2].world).y,
              0.5 * p0 + 0.125 * m0 + 0.5 * p1, 1e-5);
  EXPECT_NEAR(positionOf(flyoverAt(0.5).scene.instances[2].world).y, p1, 1e-6);
  EXPECT_NEAR(positionOf(flyoverAt(1.0).scene.instances[2].world).y, p0, 1e-6);
  // The panel, STEP: between keys 1 s and 2 s it holds key 1 (15 + 45 degrees
  // about +Y), and it does not move.
  const glm::mat4 held = flyoverAt(1.0).scene.instances[3].world;
  const glm::mat4 later = flyoverAt(1.99).scene.instances[3].world;
  EXPECT_EQ(std::memcmp(&held, &later, sizeof(glm::mat4)), 0);
  const glm::dvec3 xAxis = glm::normalize(glm::dvec3(glm::vec3(held[0])));
  EXPECT_NEAR(std::atan2(-xAxis.z, xAxis.x), 60.0 * M_PI / 180.0, 1e-6);
  EXPECT_EQ(positionOf(held), positionOf(start.scene.instances[3].world));
  // The cube, a child of the turntable (LINEAR slerp, a third of a turn in
  // 4/3 s): at 2/3 s the turntable has turned 60 degrees about +Y, so the
  // cube's centre (2.4 out on +X at rest) is there turned by 60 degrees.
  const glm::dvec3 cube = positionOf(flyoverAt(2.0 / 3.0).scene.instances[1].world);
  const double angle = 60.0 * M_PI / 180.0;
  EXPECT_NEAR(cube.x, 2.4 * std::cos(angle), 1e-5);
  EXPECT_NEAR(cube.z, -2.4 * std::sin(angle), 1e-5);
  EXPECT_NEAR(cube.y, 0.75, 1e-6);
  // The camera, on a node: LINEAR between its keys, always looking at the
  // target (0, 0.8, 0).
  for (const double t : {0.0, 0.25, 1.3, 4.0}) {
    const Posed posed = flyoverAt(t);
    const glm::mat4 world = posed.scene.cameras[0].world;
    const glm::dvec3 eye = positionOf(world);
    const glm::dvec3 forward = -glm::normalize(glm::dvec3(glm::vec3(world[2])));
    const glm::dvec3 toTarget = glm::normalize(glm::dvec3(0.0, 0.8, 0.0) - eye);
    EXPECT_NEAR(glm::dot(forward, toTarget), 1.0, 1e-4) << t;
    EXPECT_NEAR(std::hypot(eye.x, eye.z), 7.0, 0.05) << t;  // chords of a radius-7 arc
  }
  EXPECT_NE(positionOf(start.scene.cameras[0].world),
            positionOf(flyoverAt(2.0).scene.cameras[0].world));
}

TEST(Flyover, SequenceRendersFramesThatDiffer) {
  const fs::path dir = emptyFolder("flyover");
  for (const char* frames : {"0:0", "48:48"}) {
    const RunResult r =
        run(std::string("render builtin:flyover --width 64 --height 36 ") +
            "--threads 2 --sequence " + frames + " --out " + (dir / "f_##.png").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
  }
  EXPECT_NE(bytesOf(dir / "f_00.png"), bytesOf(dir / "f_48.png"));
}

}  // namespace
}  // namespace quadra
