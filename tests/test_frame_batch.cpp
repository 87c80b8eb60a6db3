// Splitting a sequence among processes and resuming it: the shard
// assignment against its definition, and `quadra render --sequence` with
// --shard, --skip-existing and --progress end to end (the CLI as a
// subprocess): shards that together write the one-process sequence byte for
// byte, a resumed sequence that renders only its missing frames, the plain
// progress lines, the EXR storage options on every file, and every bad value
// a one-line error that writes nothing.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.h"
#include "core/error.h"
#include "frame_batch.h"

namespace quadra {
namespace {

TEST(FrameBatch, ShardsTakeEveryFrameOnceRoundRobin) {
  for (int count = 1; count <= 7; ++count) {
    for (int length : {0, 1, 5, 12, 13}) {
      std::vector<int> frames;
      for (int i = 0; i < length; ++i) frames.push_back(40 + 3 * i);  // any frame numbers
      std::map<int, int> owner;
      std::size_t smallest = frames.size(), largest = 0;
      for (int index = 0; index < count; ++index) {
        const std::vector<int> mine = shardFrames(frames, Shard{index, count});
        smallest = std::min(smallest, mine.size());
        largest = std::max(largest, mine.size());
        EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end()));
        for (const int f : mine) {
          EXPECT_EQ(owner.count(f), 0u) << "frame " << f << " in two shards";
          owner[f] = index;
        }
      }
      ASSERT_EQ(owner.size(), frames.size()) << count << " shards of " << length;
      // The definition: position p goes to shard p mod count.
      for (std::size_t p = 0; p < frames.size(); ++p)
        EXPECT_EQ(owner[frames[p]], int(p % std::size_t(count)));
      EXPECT_LE(largest - std::min(smallest, largest), 1u);
    }
  }
}

TEST(FrameBatch, ParsesShardsAndRejectsTheRest) {
  const Shard shard = parseShard("--shard", "2/5");
  EXPECT_EQ(shard.index, 2);
  EXPECT_EQ(shard.count, 5);
  EXPECT_EQ(parseShard("--shard", "0/1").count, 1);
  for (const char* bad :
       {"5/5", "6/5", "-1/5", "0/0", "1", "/3", "1/", "a/b", "1/2/3", "1.5/3", ""})
    EXPECT_THROW(parseShard("--shard", bad), Error) << bad;
}

// The "quadra progress" lines of `err`, each as its key=value pairs (the
// repeated out= keys joined by spaces), in order.
std::vector<std::map<std::string, std::string>> progressLines(const std::string& err) {
  std::vector<std::map<std::string, std::string>> lines;
  std::istringstream text(err);
  for (std::string line; std::getline(text, line);) {
    if (line.rfind("quadra progress ", 0) != 0) continue;
    std::map<std::string, std::string> pairs;
    std::istringstream words(line.substr(16));
    for (std::string word; words >> word;) {
      const std::size_t eq = word.find('=');
      if (eq == std::string::npos) continue;
      std::string& value = pairs[word.substr(0, eq)];
      value += (value.empty() ? "" : " ") + word.substr(eq + 1);
    }
    lines.push_back(pairs);
  }
  return lines;
}

constexpr const char* kSmall = " --width 64 --height 48 --threads 2";

RunResult render(const std::string& arguments) {
  return run("render " + arguments + kSmall);
}

TEST(FrameBatchCli, ShardsTogetherWriteTheWholeSequence) {
  const std::string model = modelPath("AnimatedTriangle");
  if (!fs::exists(model)) GTEST_SKIP() << "no " << model;
  const fs::path whole = emptyFolder("whole"), sharded = emptyFolder("sharded");
  // Frames 5..11 at 8 fps: the triangle turns 22.5 degrees a frame.
  const RunResult one =
      render(model + " --fps 8 --sequence 5:11 --out " + (whole / "t_##.exr").string());
  ASSERT_EQ(one.exitCode, 0) << one.err;
  for (int index = 0; index < 3; ++index) {
    const RunResult r =
        render(model + " --fps 8 --sequence 5:11 --progress plain --shard " +
               std::to_string(index) + "/3 --out " + (sharded / "t_##.exr").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // Position p = frame - 5 goes to shard p mod 3.
    std::vector<std::string> frames;
    for (const auto& line : progressLines(r.err)) frames.push_back(line.at("frame"));
    const std::vector<std::vector<std::string>> expected = {
        {"5", "8", "11"}, {"6", "9"}, {"7", "10"}};
    EXPECT_EQ(frames, expected[std::size_t(index)]) << r.err;
    EXPECT_EQ(lineKeyValues(r.out, "quadra frame_ms ").at("frames"),
              std::to_string(expected[std::size_t(index)].size()));
  }
  ASSERT_EQ(fileNames(sharded), fileNames(whole));
  for (const std::string& name : fileNames(whole))
    EXPECT_EQ(bytesOf(sharded / name), bytesOf(whole / name)) << name;
  EXPECT_NE(bytesOf(whole / "t_05.exr"), bytesOf(whole / "t_06.exr"));
}

TEST(FrameBatchCli, SkipExistingRendersOnlyTheMissingFrames) {
  const std::string model = modelPath("AnimatedTriangle");
  if (!fs::exists(model)) GTEST_SKIP() << "no " << model;
  const fs::path dir = emptyFolder("resume");
  const std::string outs =
      " --out " + (dir / "t_#.exr").string() + " --out " + (dir / "t_#.png").string();
  const std::string args = model + " --fps 8 --sequence 0:3 --progress plain" + outs;
  ASSERT_EQ(render(args).exitCode, 0);
  const std::string frame2 = bytesOf(dir / "t_2.exr"), frame3 = bytesOf(dir / "t_3.png");
  // Frame 2 lost both files, frame 3 one of its two: both are rendered again.
  fs::remove(dir / "t_2.exr");
  fs::remove(dir / "t_2.png");
  fs::remove(dir / "t_3.png");
  const auto past = fs::file_time_type::clock::now() - std::chrono::hours(1);
  for (const std::string& name : fileNames(dir)) fs::last_write_time(dir / name, past);
  const RunResult r = render(args + " --skip-existing");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::vector<std::string> statuses;
  for (const auto& line : progressLines(r.err))
    statuses.push_back(line.at("frame") + ":" + line.at("status"));
  EXPECT_EQ(statuses,
            (std::vector<std::string>{"0:skipped", "1:skipped", "2:rendered", "3:rendered"}));
  EXPECT_EQ(lineKeyValues(r.out, "quadra frame_ms ").at("frames"), "2");
  EXPECT_EQ(bytesOf(dir / "t_2.exr"), frame2);
  EXPECT_EQ(bytesOf(dir / "t_3.png"), frame3);
  for (const char* untouched : {"t_0.exr", "t_0.png", "t_1.exr", "t_1.png"})
    EXPECT_EQ(fs::last_write_time(dir / untouched), past) << untouched << " was rewritten";
  EXPECT_GT(fs::last_write_time(dir / "t_3.exr"), past);

  // Nothing left to do: every frame skipped, the frame line says frames=0.
  const RunResult again = render(args + " --skip-existing");
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_EQ(lineKeyValues(again.out, "quadra frame_ms ").at("frames"), "0");
  EXPECT_EQ(again.out.find("quadra wrote"), std::string::npos) << again.out;
  EXPECT_EQ(progressLines(again.err).size(), 4u);
}

// The resumption the issue asks for: a sequence killed (SIGKILL, no chance
// to clean up) while it renders, then rerun with --skip-existing, ends with
// the same files, byte for byte, as one uninterrupted run.
TEST(FrameBatchCli, KilledSequenceResumesToTheSameFrames) {
  const std::string model = modelPath("BoxAnimated");
  if (!fs::exists(model)) GTEST_SKIP() << "no " << model;
  const fs::path whole = emptyFolder("unkilled"), killed = emptyFolder("killed");
  const std::string args = model + " --sequence 0:29 --width 320 --height 180 --threads 2";
  const RunResult full = run("render " + args + " --out " + (whole / "b_##.exr").string());
  ASSERT_EQ(full.exitCode, 0) << full.err;
  // Killed as soon as its third frame is on disk (or when it has ended).
  const std::string script = std::string(QUADRA_CLI_PATH) + " render " + args + " --out " +
                             (killed / "b_##.exr").string() +
                             " >/dev/null & pid=$!; while kill -0 $pid 2>/dev/null && [ ! -e " +
                             (killed / "b_02.exr").string() +
                             " ]; do sleep 0.005; done; kill -9 $pid 2>/dev/null; wait $pid; true";
  ASSERT_EQ(runProgram("bash", "-c '" + script + "'").exitCode, 0);
  std::size_t before = 0;
  for (const std::string& name : fileNames(killed)) {
    if (name.find(".tmp-") != std::string::npos) continue;  // an interrupted write
    EXPECT_EQ(bytesOf(killed / name), bytesOf(whole / name)) << name << " is not whole";
    ++before;
  }
  EXPECT_GE(before, 3u);
  const RunResult resumed = run("render " + args + " --skip-existing --progress plain --out " +
                                (killed / "b_##.exr").string());
  ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
  EXPECT_EQ(lineKeyValues(resumed.out, "quadra frame_ms ").at("frames"),
            std::to_string(30 - before));
  for (const std::string& name : fileNames(whole))
    EXPECT_EQ(bytesOf(killed / name), bytesOf(whole / name)) << name;
}

TEST(FrameBatchCli, PlainProgressCountsFramesAndPaths) {
  const fs::path dir = emptyFolder("plain");
  const RunResult r = render("builtin:showcase --sequence 3:6 --progress plain --out " +
                             (dir / "s_###.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto lines = progressLines(r.err);
  ASSERT_EQ(lines.size(), 4u) << r.err;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto& line = lines[i];
    EXPECT_EQ(line.at("frame"), std::to_string(3 + i));
    EXPECT_EQ(line.at("status"), "rendered");
    EXPECT_EQ(line.at("done"), std::to_string(i + 1));
    EXPECT_EQ(line.at("total"), "4");
    EXPECT_GT(std::stod(line.at("ms")), 0.0);
    EXPECT_GT(std::stod(line.at("fps")), 0.0);
    EXPECT_EQ(line.at("out"), (dir / ("s_00" + std::to_string(3 + i) + ".png")).string());
    EXPECT_TRUE(fs::exists(line.at("out")));
    // The estimate is the frames left at the measured rate. Both figures are printed rounded
    // (eta_s to 0.05, fps to 0.0005), and a slow frame makes left / fps sensitive to the latter.
    const double left = double(lines.size() - i - 1);
    const double fps = std::stod(line.at("fps"));
    const double fpsRounding = left * 0.0005 / ((fps - 0.0005) * fps);
    EXPECT_NEAR(std::stod(line.at("eta_s")), left / fps, 0.05 + fpsRounding + 1e-6);
  }
  EXPECT_EQ(lines.back().at("eta_s"), "0.0");
  // Without --progress and away from a terminal: no progress at all.
  const RunResult quiet =
      render("builtin:showcase --sequence 3:4 --out " + (dir / "q_#.png").string());
  ASSERT_EQ(quiet.exitCode, 0);
  EXPECT_EQ(quiet.err, "");
}

TEST(FrameBatchCli, BarRedrawsOneLine) {
  const fs::path dir = emptyFolder("bar");
  const RunResult r =
      render("builtin:showcase --sequence 0:2 --progress bar --out " + (dir / "b_#.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // One line drawn and erased in place (\r), ended once at the end; its
  // last drawing is the finished sequence.
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  ASSERT_EQ(r.err.back(), '\n');
  const std::string last = r.err.substr(r.err.rfind('\r'));
  EXPECT_NE(last.find("3/3 frames"), std::string::npos) << r.err;
  EXPECT_NE(last.find("frames/s"), std::string::npos) << r.err;
  EXPECT_NE(last.find("ETA 0:00"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("1/3 frames"), std::string::npos) << r.err;
}

// Without --progress the bar shows where stderr is a terminal: here a
// pseudo-terminal from util-linux's `script`, which copies it to stdout.
TEST(FrameBatchCli, TerminalGetsTheBarByDefault) {
  if (std::system("command -v script >/dev/null 2>&1") != 0) GTEST_SKIP() << "no script(1)";
  const fs::path dir = emptyFolder("terminal");
  const std::string command = std::string(QUADRA_CLI_PATH) +
                              " render builtin:showcase --width 64 --height 48 --threads 2 "
                              "--sequence 0:1 --out " +
                              (dir / "t_#.png").string();
  const RunResult r = runProgram("script", "-qec '" + command + "' /dev/null");
  ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("] 2/2 frames"), std::string::npos) << r.out;
}

TEST(FrameBatchCli, ShardPastTheEndRendersNothing) {
  const fs::path dir = emptyFolder("past");
  const RunResult r =
      render("builtin:showcase --sequence 0:1 --shard 5/8 --out " + (dir / "p_#.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::is_empty(dir));
  EXPECT_EQ(lineKeyValues(r.out, "quadra frame_ms ").at("frames"), "0");
}

// --exr-compression and --exr-colour reach every frame of a sequence and a
// still (through the writer thread and the still's writer alike), and
// without them the files are what they were: ZIP, FLOAT colour.
TEST(FrameBatchCli, ExrStorageOptionsReachEveryFile) {
  const fs::path dir = emptyFolder("exr_storage");
  const std::string size = "builtin:flyover --width 48 --height 32 ";
  struct Case {
    std::string options;
    Imf::Compression compression;
    Imf::PixelType colour;
  };
  const Case cases[] = {
      {"", Imf::ZIP_COMPRESSION, Imf::FLOAT},
      {"--exr-compression piz --exr-colour half", Imf::PIZ_COMPRESSION, Imf::HALF},
      {"--exr-compression none", Imf::NO_COMPRESSION, Imf::FLOAT},
      {"--exr-colour half --exr-compression rle", Imf::RLE_COMPRESSION, Imf::HALF}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.options);
    fs::remove_all(dir);
    fs::create_directories(dir);
    ASSERT_EQ(render(size + "--sequence 0:1 --out " + (dir / "f_#.exr").string() + " " + c.options)
                  .exitCode,
              0);
    ASSERT_EQ(render(size + "--out " + (dir / "still.exr").string() + " " + c.options).exitCode, 0);
    for (const char* name : {"f_0.exr", "f_1.exr", "still.exr"}) {
      Imf::InputFile in((dir / name).string().c_str());
      EXPECT_EQ(in.header().compression(), c.compression) << name;
      for (const char* channel : {"R", "G", "B", "A"})
        EXPECT_EQ(in.header().channels().findChannel(channel)->type, c.colour) << name;
      EXPECT_EQ(in.header().channels().findChannel("Z")->type, Imf::FLOAT) << name;
    }
  }
}

TEST(FrameBatchCli, BadBatchInputIsOneLineAndWritesNothing) {
  const fs::path dir = emptyFolder("bad_batch");
  const std::string seq = "builtin:showcase --sequence 0:3 --out " + (dir / "f_#.png").string();
  const std::string still = "builtin:showcase --out " + (dir / "f.png").string();
  struct Case {
    std::string arguments, mentions;
  };
  const Case cases[] = {
      {seq + " --shard 3/3", "--shard: '3/3': shard 3 is outside 0..2"},
      {seq + " --shard -1/3", "--shard"},
      {seq + " --shard 0/0", "--shard: '0'"},
      {seq + " --shard 1", "--shard: '1' must be I/N"},
      {seq + " --shard a/b", "--shard"},
      {seq + " --shard 1/", "must be I/N"},
      {seq + " --progress fancy", "--progress: unknown progress display 'fancy'"},
      {"builtin:showcase --sequence 0:3 --skip-existing", "--skip-existing: needs an --out"},
      {still + " --shard 0/2", "--shard: only with --sequence"},
      {still + " --skip-existing", "--skip-existing: only with --sequence"},
      {still + " --progress plain", "--progress: only with --sequence"},
      // The EXR storage options: a known name, and an EXR to apply to.
      {seq + " --exr-compression zip", "--exr-compression: no --out is an .exr file"},
      {still + " --exr-colour half", "--exr-colour: no --out is an .exr file"},
      {"builtin:showcase --exr-compression none", "--exr-compression: no --out is an .exr file"},
      {still + " --exr-compression dwaa",
       "--exr-compression: 'dwaa' is not an EXR compression quadra writes (valid: none, rle, "
       "zips, zip, piz)"},
      {"builtin:showcase --sequence 0:3 --out " + (dir / "f_#.exr").string() +
           " --exr-colour double",
       "--exr-colour: 'double' is not an EXR colour type (valid: float, half)"},
  };
  for (const Case& c : cases) {
    const RunResult r = render(c.arguments);
    EXPECT_EQ(r.exitCode, 2) << c.arguments;  // each the command line's fault
    expectOneLineError(r, c.mentions);
    EXPECT_TRUE(fs::is_empty(dir)) << c.arguments << " wrote a file";
  }
}

}  // namespace
}  // namespace quadra
