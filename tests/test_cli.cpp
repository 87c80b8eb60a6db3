// The command-line contracts of DESIGN.md, exercised on the built binary:
// the `quadra frame_ms` and `quadra sample_ns` lines, outputs, and one-line
// errors with a non-zero exit and no output file left behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "cli_helpers.h"
#include "cli_options.h"
#include "io/image_io.h"
#include "param_names.h"
#include "render_options.h"

namespace quadra {
namespace {

TEST(Cli, RenderPrintsTheFrameLineAndWritesBothFormats) {
  const fs::path exr = tempPath("cli.exr"), png = tempPath("cli.png");
  const RunResult r =
      run("render builtin:checker-plane --width 96 --height 54 --frames 3 --threads 2 "
          "--filter trilinear --out " +
          exr.string() + " --out " + png.string());
  expectCheckerPlaneFrame(r, "quadra frame_ms ", exr, png);
}

TEST(Cli, StatsPrintEveryStageAsANumber) {
  const fs::path png = tempPath("stats.png");
  const RunResult r = run(
      "render builtin:showcase --width 96 --height 54 --frames 3 --stats --out " + png.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto stages = lineKeyValues(r.out, "quadra stages_ms ");
  const char* const keys[] = {"load", "first_frame", "env",   "draws",   "vertex", "setup",
                              "bin",  "raster",      "shade", "resolve", "write"};
  EXPECT_EQ(stages.size(), std::size(keys)) << r.out;
  for (const char* key : keys) {
    ASSERT_TRUE(stages.count(key)) << key << " missing in: " << r.out;
    std::size_t used = 0;
    const double ms = std::stod(stages.at(key), &used);
    EXPECT_EQ(used, stages.at(key).size()) << key << "=" << stages.at(key);
    EXPECT_GE(ms, 0.0) << key;
  }
  EXPECT_GT(std::stod(stages.at("raster")), 0.0);
  EXPECT_GT(std::stod(stages.at("write")), 0.0);  // a PNG was written
  // pbr by default: the warm-up frame prepared the environment.
  EXPECT_GT(std::stod(stages.at("env")), 0.0);
  EXPECT_LE(std::stod(stages.at("env")), std::stod(stages.at("first_frame")));
  // An unlit frame has no environment to prepare.
  const RunResult unlit =
      run("render builtin:showcase --shading unlit --width 16 --height 16 --stats");
  const auto unlitStages = lineKeyValues(unlit.out, "quadra stages_ms ");
  ASSERT_TRUE(unlitStages.count("env")) << unlit.out;
  EXPECT_EQ(unlitStages.at("env"), "0.000");
  // Without --stats the line is not printed.
  EXPECT_TRUE(
      lineKeyValues(run("render builtin:showcase --width 16 --height 16").out, "quadra stages_ms ")
          .empty());
}

TEST(Cli, CameraOverridesChangeTheImage) {
  const fs::path a = tempPath("cam_a.exr"), b = tempPath("cam_b.exr");
  ASSERT_EQ(run("render builtin:checker-plane --width 64 --height 36 --out " + a.string()).exitCode,
            0);
  ASSERT_EQ(run("render builtin:checker-plane --width 64 --height 36 --eye 0,3,2 --target 0,0,-5 "
                "--up 0,1,0 --fovy 40 --near 0.1 --far 500 --out " +
                b.string())
                .exitCode,
            0);
  EXPECT_NE(readImage(a.string()).rgba, readImage(b.string()).rgba);
}

// Exit status 2 for a command line wrong in itself, 1 for input that fails
// (cli_options.h UsageError).
TEST(Cli, BadOptionsAreOneLineErrorsAndWriteNothing) {
  const fs::path out = tempPath("never.png");
  const std::string scene = "render builtin:checker-plane ", to = " --out " + out.string();
  struct Case {
    std::string arguments, mentions;
    int exitCode;
  };
  const Case cases[] = {
      {scene + "--width 0" + to, "--width", 2},
      {scene + "--filter sharpest" + to, "--filter", 2},
      {scene + "--isa mmx" + to, "--isa", 2},
      {scene + "--eye 1,2" + to, "--eye", 2},
      {scene + "--out " + tempPath("x.bmp").string(), ".bmp", 2},
      {"render builtin:no-such-scene" + to, "no-such-scene", 2},
      {"render /nonexistent/model.gltf" + to, "/nonexistent/model.gltf", 1},
      {scene + "--frobnicate 1", "--frobnicate", 2},
      {scene + "--texture-format rgba4" + to, "--texture-format", 2},
      {scene + "--depth inverted" + to, "--depth", 2},
      {scene + "--pixel-filter gaussian" + to, "--pixel-filter", 2},
      {scene + "--aov mask,curvature" + to, "'curvature'", 2},
      {"render builtin:checker-plane builtin:showcase" + to, "more than one scene", 2},
      {"sample --filter bilinear --in a.csv --out b.csv", "--texture is required", 2},
  };
  for (const Case& c : cases) {
    const RunResult r = run(c.arguments);
    EXPECT_EQ(r.exitCode, c.exitCode) << c.arguments;
    expectOneLineError(r, c.mentions);
  }
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, UnwritableOutputFailsWithoutPartialFile) {
  const RunResult r =
      run("render builtin:checker-plane --width 32 --height 32 --out "
          "/nonexistent-dir/frame.exr");
  expectOneLineError(r, "/nonexistent-dir/frame.exr");
}

TEST(Cli, MalformedGltfIsAOneLineError) {
  const fs::path bad = tempPath("bad.gltf");
  std::ofstream(bad) << "{ \"asset\": {\"version\": \"2.0\"}, \"meshes\": [ {";
  expectOneLineError(run("render " + bad.string() + " --width 32 --height 32"), bad.string());
}

// The scene sandbox: a glTF whose buffer lies outside its folder is refused
// (one line naming the file and the URI, exit 1, nothing written) until
// --allow-path names the folder the buffer is in.
TEST(Cli, GltfReadingOutsideItsFolderIsRefusedUnlessAllowed) {
  const fs::path root = testDir() / "sandbox";
  fs::remove_all(root);
  fs::create_directories(root / "scene");
  fs::create_directories(root / "outside");
  const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::ofstream(root / "outside" / "triangle.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(triangle), sizeof triangle);
  const fs::path gltf = root / "scene" / "triangle.gltf";
  std::ofstream(gltf) << R"({"asset":{"version":"2.0"},
    "buffers":[{"byteLength":36,"uri":"../outside/triangle.bin"}],
    "bufferViews":[{"buffer":0,"byteLength":36}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
  const fs::path out = tempPath("sandboxed.png");
  const std::string render =
      "render " + gltf.string() + " --width 32 --height 32 --out " + out.string();

  const RunResult refused = run(render);
  expectOneLineError(refused, gltf.string() + ": URI '../outside/triangle.bin' resolves to ");
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_FALSE(fs::exists(out));

  const std::string nowhere = (root / "nowhere").string();
  const RunResult missing = run(render + " --allow-path " + nowhere);
  expectOneLineError(missing, "--allow-path: '" + nowhere + "' is not an existing folder");
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_FALSE(fs::exists(out));

  const RunResult allowed = run(render + " --allow-path " + (root / "scene").string() +
                                " --allow-path " + (root / "outside").string());
  EXPECT_EQ(allowed.exitCode, 0) << allowed.err;
  EXPECT_TRUE(fs::exists(out));
  fs::remove_all(root);
}

// One triangle in a data URI, with the given extension lists.
fs::path triangleWithExtensions(const std::string& name, const std::string& extensions) {
  const fs::path path = tempPath(name);
  std::ofstream(path)
      << "{\"asset\":{\"version\":\"2.0\"}," << extensions
      << "\"buffers\":[{\"byteLength\":36,\"uri\":\"data:application/octet-stream;base64,"
         "AAAAvwAAAL8AAAAAAAAAPwAAAL8AAAAAAAAAAAAAAD8AAAAA\"}],"
         "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
         "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":"
         "\"VEC3\",\"min\":[-0.5,-0.5,0],\"max\":[0.5,0.5,0]}],"
         "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
         "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]}";
  return path;
}

// A required extension quadra does not implement would draw the scene wrong:
// exit 1, one line naming the file and the extension, nothing written. An
// optional one is drawn without: one note line, exit 0.
TEST(Cli, UnimplementedExtensionsRequiredAreErrorsOptionalAreNotes) {
  const fs::path out = tempPath("extension.png");
  const fs::path required =
      triangleWithExtensions("required.gltf",
                             "\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
                             "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],");
  const RunResult r =
      run("render " + required.string() + " --width 32 --height 32 --out " + out.string());
  EXPECT_EQ(r.exitCode, 1);
  expectOneLineError(r, required.string() +
                            ": unsupported required extension "
                            "KHR_draco_mesh_compression");
  EXPECT_FALSE(fs::exists(out));

  const fs::path optional = triangleWithExtensions(
      "optional.gltf",
      "\"extensionsUsed\":[\"KHR_materials_sheen\",\"KHR_texture_transform\"],"
      "\"extensionsRequired\":[\"KHR_texture_transform\"],");
  const RunResult o =
      run("render " + optional.string() + " --width 32 --height 32 --out " + out.string());
  EXPECT_EQ(o.exitCode, 0) << o.err;
  EXPECT_EQ(o.err, "quadra: note: " + optional.string() +
                       ": optional extension KHR_materials_sheen is not supported; ignored\n");
  EXPECT_TRUE(fs::exists(out));
}

TEST(Cli, SampleReadsLookupsAndWritesValuesInOrder) {
  // A 2x1 texture: left texel linear 0, right texel linear 1 (an EXR, read as linear).
  Frame texture;
  texture.width = 2;
  texture.height = 1;
  texture.rgba = {0, 0, 0, 1, 1, 1, 1, 1};
  texture.depth = {1, 1};
  const fs::path tex = tempPath("tex.exr"), in = tempPath("lookups.csv"),
                 out = tempPath("values.csv");
  writeFrame(texture, tex.string());
  // Texel centres sit at u = 0.25 and 0.75; halfway between them bilinear gives 0.5.
  std::ofstream(in)
      << "u,v,dudx,dvdx,dudy,dvdy\n0.25,0.5,0,0,0,0\n0.5,0.5,0,0,0,0\n0.75,0.5,0,0,0,0\n";
  const RunResult r =
      run("sample --texture " + tex.string() + " --filter bilinear --wrap clamp --in " +
          in.string() + " --out " + out.string() + " --threads 1");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto line = lineKeyValues(r.out, "quadra sample_ns ");
  for (const char* key : {"per_lookup", "lookups", "threads", "isa"}) EXPECT_TRUE(line.count(key));
  EXPECT_EQ(line.at("lookups"), "3");
  std::ifstream values(out);
  std::string header, row;
  std::getline(values, header);
  EXPECT_EQ(header, "r,g,b,a");
  const double expected[3] = {0.0, 0.5, 1.0};
  for (double e : expected) {
    ASSERT_TRUE(std::getline(values, row));
    EXPECT_NEAR(std::stod(row.substr(0, row.find(','))), e, 1e-6) << row;
  }

  // The same lookups from each narrow storage format (0 and 1 are exact in
  // all, so the midpoint is too); an unknown format is a one-line error.
  for (const char* format : {"rgba16f", "rgba8", "rgba8srgb"}) {
    ASSERT_EQ(run("sample --texture " + tex.string() + " --filter bilinear --wrap clamp --in " +
                  in.string() + " --out " + out.string() + " --format " + format)
                  .exitCode,
              0)
        << format;
    std::ifstream narrow(out);
    std::getline(narrow, header);
    for (double e : expected) {
      ASSERT_TRUE(std::getline(narrow, row));
      EXPECT_NEAR(std::stod(row.substr(0, row.find(','))), e, 1e-6) << format << " " << row;
    }
  }
  expectOneLineError(run("sample --texture " + tex.string() + " --filter bilinear --in " +
                         in.string() + " --out " + out.string() + " --format rgba4"),
                     "--format");
}

TEST(Cli, SampleRejectsMalformedCsv) {
  const fs::path tex = tempPath("tex2.exr"), in = tempPath("bad.csv"), out = tempPath("never.csv");
  Frame texture;
  texture.width = texture.height = 1;
  texture.rgba = {1, 1, 1, 1};
  texture.depth = {1};
  writeFrame(texture, tex.string());
  std::ofstream(in) << "u,v,dudx,dvdx,dudy,dvdy\n0.5,0.5,0,0,0\n";
  const RunResult r = run("sample --texture " + tex.string() + " --filter bilinear --in " +
                          in.string() + " --out " + out.string());
  expectOneLineError(r, in.string() + ": line 2");
  EXPECT_FALSE(fs::exists(out));
}

// One command with a valid command line split in two, so an option can go
// first, between them, or last; `written` is what a run would create.
struct CommandLineCase {
  std::string command, head, tail;
  fs::path written;
};

// Valid and quick (where they run at all): an option the parser ignored
// would let the command run and write, failing the "nothing written" checks.
std::vector<CommandLineCase> everyCommand() {
  Frame texture;
  texture.width = texture.height = 2;
  texture.rgba.assign(16, 0.5f);
  texture.depth.assign(4, 1.0f);
  const fs::path tex = tempPath("parse_tex.exr"), in = tempPath("parse_lookups.csv");
  writeFrame(texture, tex.string());
  std::ofstream(in) << "u,v,dudx,dvdx,dudy,dvdy\n0.5,0.5,0,0,0,0\n";
  const fs::path png = tempPath("parse.png"), csv = tempPath("parse_values.csv"),
                 reportDir = testDir() / "parse_report", framesDir = testDir() / "parse_frames",
                 samplesDir = testDir() / "parse_samples",
                 lightingDir = testDir() / "parse_lighting";
  fs::remove_all(reportDir);
  fs::remove_all(framesDir);
  fs::remove_all(samplesDir);
  fs::remove_all(lightingDir);
  return {
      {"render", "builtin:checker-plane --width 32", "--height 32 --out " + png.string(), png},
      {"sample", "--texture " + tex.string() + " --filter bilinear",
       "--in " + in.string() + " --out " + csv.string(), csv},
      {"report textures", "--size 8 --lookups 36", "--out-dir " + reportDir.string(), reportDir},
      {"report sat-precision", "--size 16", "--boxes 1", {}},
      {"report stability", "--threads 2", "--isa auto", {}},
      {"report frames", "--scenes builtin:checker-plane --width 32",
       "--height 32 --rounds 1 --frames 1 --out-dir " + framesDir.string(), framesDir},
      {"report samples", "--scenes builtin:checker-plane --width 32",
       "--height 32 --samples 1 --reference-spp 1 --rounds 1 --frames 1 --out-dir " +
           samplesDir.string(),
       samplesDir},
      {"report lighting", "--scenes builtin:checker-plane --envs builtin:studio",
       "--accuracy-size 8x8 --speed-size 8x8 --rounds 1 --frames 1 --llvmpipe-ibl-size 32 "
       "--llvmpipe-lut-size 64 --out-dir " +
           lightingDir.string(),
       lightingDir},
  };
}

// Exit status 2: the command line is wrong in itself (cli_options.h UsageError).
void expectUsageError(const RunResult& r, const std::string& message, const fs::path& written) {
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(r.err, "quadra: " + message + "\n");
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(written.empty() || !fs::exists(written)) << written;
}

TEST(Cli, UnknownOptionIsAnErrorWhereverItStands) {
  for (const CommandLineCase& c : everyCommand()) {
    const std::string unknown =
        c.command + ": unknown option '--bogus' (see quadra " + c.command + " --help)";
    for (const std::string& line : {c.command + " --bogus " + c.head + " " + c.tail,
                                    c.command + " " + c.head + " --bogus " + c.tail,
                                    c.command + " " + c.head + " " + c.tail + " --bogus",
                                    c.command + " " + c.head + " --bogus 1 " + c.tail}) {
      SCOPED_TRACE(line);
      expectUsageError(run(line), unknown, c.written);
    }
  }
}

TEST(Cli, KnownOptionWithoutItsValueIsMissingValue) {
  for (const CommandLineCase& c : everyCommand())
    for (const std::string& line : {c.command + " " + c.head + " " + c.tail + " --threads",
                                    c.command + " " + c.head + " --threads " + c.tail}) {
      SCOPED_TRACE(line);
      expectUsageError(run(line), "--threads: missing value", c.written);
    }
  // An undeclared option outranks a missing value, wherever each stands.
  expectUsageError(run("render --width --bogus"),
                   "render: unknown option '--bogus' (see quadra render --help)", {});
}

TEST(Cli, HelpPrintsTheCommandsUsage) {
  for (const CommandLineCase& c : everyCommand()) {
    SCOPED_TRACE(c.command);
    const RunResult r = run(c.command + " " + c.head + " --help --bogus");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.rfind("usage: quadra " + c.command + " ", 0), 0u) << r.out;
    EXPECT_EQ(r.err, "");
    EXPECT_TRUE(c.written.empty() || !fs::exists(c.written)) << c.written;
  }
}

TEST(Cli, SharedOptionsSayTheSameWhicheverCommandHasThem) {
  for (const CommandLineCase& c : everyCommand()) {
    SCOPED_TRACE(c.command);
    expectUsageError(run(c.command + " " + c.head + " " + c.tail + " --threads 0"),
                     "--threads: '0' must be a whole number in 1..1024", c.written);
    if (c.command == "report sat-precision" || c.command == "report frames" ||
        c.command == "report lighting")
      continue;  // no --isa
    expectUsageError(run(c.command + " " + c.head + " " + c.tail + " --isa mmx"),
                     "--isa: unknown ISA 'mmx' (auto, scalar, sse2, avx2, avx512)", c.written);
  }
  for (const char* command : {"render builtin:checker-plane", "sample"})
    expectUsageError(run(std::string(command) + " --lod-bias 33"),
                     "--lod-bias: must lie in -32..32", {});
  // Every command that loads glTF files takes --allow-path and --max-memory,
  // and checks them even when its scenes are built in. A folder that does
  // not exist is bad input (exit 1), as a missing scene file is.
  for (const CommandLineCase& c : everyCommand()) {
    if (c.command != "render" && c.command != "report frames" && c.command != "report samples")
      continue;
    SCOPED_TRACE(c.command);
    const RunResult missing =
        run(c.command + " " + c.head + " " + c.tail + " --allow-path /nonexistent");
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_EQ(missing.err, "quadra: --allow-path: '/nonexistent' is not an existing folder\n");
    EXPECT_TRUE(c.written.empty() || !fs::exists(c.written)) << c.written;
    expectUsageError(run(c.command + " " + c.head + " " + c.tail + " --max-memory 12Q"),
                     "--max-memory: '12Q' is not a size (bytes, or a number with K, M, G or T, "
                     "1024-based: 512M, 4G)",
                     c.written);
  }
}

TEST(Cli, VersionPrintsTheProjectVersion) {
  const RunResult r = run("--version");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out, std::string("quadra ") + QUADRA_VERSION_STRING + "\n");
  EXPECT_TRUE(std::regex_match(r.out, std::regex("quadra [0-9]+\\.[0-9]+\\.[0-9]+\n"))) << r.out;
  EXPECT_EQ(r.err, "");
}

TEST(Cli, UnknownTopLevelArgumentIsAOneLineError) {
  const RunResult r = run("--bogus");
  EXPECT_EQ(r.exitCode, 2);
  expectOneLineError(r, "unknown command '--bogus'");
  EXPECT_EQ(r.out, "");
}

// ---- help, suggestions and exit statuses ------------------------------------------

TEST(Cli, HelpListsEveryCommandAndHelpCommandIsCommandHelp) {
  const RunResult overview = run("help");
  EXPECT_EQ(overview.exitCode, 0) << overview.err;
  EXPECT_EQ(overview.err, "");
  EXPECT_EQ(overview.out.rfind("usage: quadra COMMAND", 0), 0u) << overview.out;
  EXPECT_EQ(run("--help").out, overview.out);
  const RunResult bare = run("");
  EXPECT_EQ(bare.exitCode, 2);  // nothing asked: a usage mistake, with the overview
  EXPECT_EQ(bare.out, overview.out);

  const std::vector<std::string> commands = commandsInOverview(overview.out);
  EXPECT_EQ(commands,
            (std::vector<std::string>{"render", "sample", "env", "report textures",
                                      "report sat-precision", "report stability", "report frames",
                                      "report samples", "report lighting"}));
  for (const std::string& command : commands) {
    SCOPED_TRACE(command);
    const RunResult help = run("help " + command), own = run(command + " --help"),
                    shortForm = run(command + " -h");
    EXPECT_EQ(help.exitCode, 0) << help.err;
    EXPECT_EQ(own.exitCode, 0) << own.err;
    EXPECT_EQ(help.out, own.out);
    EXPECT_EQ(shortForm.out, own.out);
    EXPECT_EQ(own.out.rfind("usage: quadra " + command + " ", 0), 0u) << own.out;
    // A command's help is its own: no other command's usage in it.
    for (const std::string& other : commands) {
      if (other == command) continue;
      EXPECT_EQ(own.out.find("usage: quadra " + other), std::string::npos) << other;
    }
  }
  // `quadra report --help` lists the subjects, as `quadra help report` does.
  const RunResult report = run("report --help");
  EXPECT_EQ(report.exitCode, 0) << report.err;
  EXPECT_EQ(run("help report").out, report.out);
  for (const char* subject : {"textures", "sat-precision", "stability", "frames", "samples"})
    EXPECT_NE(report.out.find(std::string("\n  ") + subject + " "), std::string::npos) << subject;
}

TEST(Cli, MistypedNamesGetASuggestionAndExitStatus2) {
  struct Case {
    std::string arguments, error;
  };
  const Case cases[] = {
      {"render --smaples 4", "render: unknown option '--smaples' (did you mean --samples?)"},
      {"render --filter trilinera",
       "--filter: unknown filter 'trilinera' (nearest, bilinear, nearest-mip, trilinear, aniso, "
       "ewa, area, sat, ripmap) (did you mean trilinear?)"},
      {"rendr builtin:showcase", "unknown command 'rendr' (did you mean render?)"},
      {"help rendr", "unknown command 'rendr' (did you mean render?)"},
      {"report frame", "report: unknown subject 'frame' (did you mean frames?)"},
      {"report textures --out x",
       "report textures: unknown option '--out' (did you mean "
       "--out-dir?)"},
      {"render --exr",
       "render: unknown option '--exr' (did you mean --exr-compression or "
       "--exr-colour?)"},
      {"render --progres plain", "render: unknown option '--progres' (did you mean --progress?)"},
      {"render builtin:showcse --width 8 --height 8",
       "builtin:showcse: unknown built-in scene (known: "},
      {"render --aov N,uvv", "--aov: 'uvv' is not an AOV quadra writes"},
      {"sample --wrap clmap",
       "--wrap: unknown wrap mode 'clmap' (repeat, mirror, clamp, border) "
       "(did you mean clamp?)"},
      {"report stability --sections determinsm", "--sections: unknown section 'determinsm' ("},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.arguments);
    const RunResult r = run(c.arguments);
    EXPECT_EQ(r.exitCode, 2);
    expectOneLineError(r, c.error);
    EXPECT_EQ(r.err.rfind("quadra: ", 0), 0u) << r.err;
    EXPECT_EQ(r.out, "");
  }
  EXPECT_NE(run("render builtin:showcse").err.find("(did you mean showcase?)"), std::string::npos);
  EXPECT_NE(run("render --aov N,uvv").err.find("(did you mean uv?)"), std::string::npos);
  EXPECT_NE(run("report stability --sections determinsm").err.find("(did you mean determinism?)"),
            std::string::npos);
  // Nothing close: the pointer to --help instead.
  expectUsageError(run("render --bogus"),
                   "render: unknown option '--bogus' (see quadra render --help)", {});
}

TEST(Cli, BadInputExitsWith1) {
  const RunResult missing = run("render /nonexistent/model.gltf --width 8 --height 8");
  EXPECT_EQ(missing.exitCode, 1);
  expectOneLineError(missing, "/nonexistent/model.gltf");
  const RunResult sample = run(
      "sample --texture /nonexistent/t.png --filter bilinear --in /nonexistent/l.csv --out v.csv");
  EXPECT_EQ(sample.exitCode, 1);
  expectOneLineError(sample, "/nonexistent/t.png");
}

// `quadra report` is quadra-report beside quadra, run in quadra's place
// (tools/quadra_main.cpp): its exit status is the command's, and a quadra
// without it says in one line which target builds it.
TEST(Cli, ReportRunsTheProgramBesideQuadraOrNamesItsTarget) {
  const RunResult bad =
      run("report textures --size 8 --lookups 36 --texture /nonexistent/t.png "
          "--out-dir " +
          (testDir() / "report_bad_input").string());
  EXPECT_EQ(bad.exitCode, 1);
  expectOneLineError(bad, "/nonexistent/t.png");
  EXPECT_EQ(bad.err.rfind("quadra: ", 0), 0u) << bad.err;

  const fs::path alone = emptyFolder("quadra_alone") / "quadra";
  fs::copy_file(QUADRA_CLI_PATH, alone);
  for (const char* arguments : {"report textures --size 8", "report --help", "help report"}) {
    SCOPED_TRACE(arguments);
    const RunResult r = runProgram(alone.string(), arguments);
    EXPECT_EQ(r.exitCode, 1);
    expectOneLineError(r, "quadra-report is not beside this quadra");
    EXPECT_NE(r.err.find("cmake --build build --target quadra-report"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
  }
  // What quadra itself answers still works without it.
  const RunResult overview = runProgram(alone.string(), "help");
  EXPECT_EQ(overview.exitCode, 0) << overview.err;
  EXPECT_EQ(overview.out, run("help").out);
}

// The suggestions themselves: close slips and unique prefixes, nothing for
// an unrelated name, ties named together.
TEST(CliSuggestions, NameTheClosestKnownNames) {
  const std::vector<std::string> options = {"--samples", "--shading", "--shading-rate",
                                            "--width",   "--out",     "--out-dir"};
  EXPECT_EQ(didYouMean("--smaples", options), " (did you mean --samples?)");
  EXPECT_EQ(didYouMean("--SAMPLES", options), " (did you mean --samples?)");
  EXPECT_EQ(didYouMean("--widht", options), " (did you mean --width?)");
  EXPECT_EQ(didYouMean("--shad", options), " (did you mean --shading or --shading-rate?)");
  EXPECT_EQ(didYouMean("--out-di", options), " (did you mean --out-dir?)");
  EXPECT_EQ(didYouMean("--bogus", options), "");
  EXPECT_EQ(didYouMean("--bogus", "--boxes"), "");  // two slips in five letters: too many
  EXPECT_EQ(didYouMean("--", options), "");
  EXPECT_EQ(didYouMean("--w", options), "");  // one letter is no prefix to go by
  EXPECT_EQ(didYouMean("mmx", "auto, scalar, sse2, avx2, avx512"), "");
  EXPECT_EQ(didYouMean("avx", "auto, scalar, sse2, avx2, avx512"),
            " (did you mean avx2 or avx512?)");
  EXPECT_EQ(didYouMean("z", "Z, N, P, uv"), " (did you mean Z?)");
  EXPECT_EQ(didYouMean("trilinera", "nearest, bilinear, trilinear"), " (did you mean trilinear?)");
}

}  // namespace
// `quadra report stability` end to end: every hard case of
// lab/scene/hard_case_scenes.h rendered by the engine and held to the
// double-precision references (tools/report_stability.cpp); in the sanitizer
// builds this is also the "no crash, no sanitizer report" check on them.
// The stability report in parts (`--sections`), so its longest part, the
// random triangles' coverage per sample against the reference, does not hold
// up the rest; each part names the cases it checks.
struct StabilitySections {
  std::string sections;
  std::vector<std::string> cases;
};

class StabilityReport : public ::testing::TestWithParam<StabilitySections> {};

TEST_P(StabilityReport, PassesEveryCheck) {
  const StabilitySections& part = GetParam();
  const RunResult r = run("report stability --threads 2 --sections " + part.sections);
  EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("failed=0"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("FAIL"), std::string::npos) << r.out;
  for (const std::string& scene : part.cases)
    EXPECT_NE(r.out.find("\n" + scene + " "), std::string::npos) << scene;
}

// Together every section and every hard case.
INSTANTIATE_TEST_SUITE_P(
    Cli, StabilityReport,
    ::testing::Values(
        StabilitySections{"perspective,coverage,samples,invalid-input,z-fighting,lod,determinism",
                          {"near-plane", "huge-1e6", "huge-1e30", "grazing", "slivers",
                           "watertight", "closed-mesh", "invalid-input", "z-fighting",
                           "shared-edge", "subpixel-plane", "showcase"}},
        StabilitySections{"random-triangles", {"random-triangles"}},
        StabilitySections{"samples-random-triangles", {"random-triangles"}}),
    [](const ::testing::TestParamInfo<StabilitySections>& info) {
      return asTestName(info.param.sections.substr(0, info.param.sections.find(',')));
    });

TEST(Cli, StabilityReportRejectsBadOptions) {
  RunResult r = run("report stability --isa mmx");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("--isa: unknown ISA 'mmx'"), std::string::npos) << r.err;
  r = run("report stability --sections lod,frobnicate");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("--sections: unknown section 'frobnicate'"), std::string::npos) << r.err;
  r = run("report stability --frobnicate 1");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("report stability: unknown option '--frobnicate'"), std::string::npos)
      << r.err;
}

}  // namespace quadra
