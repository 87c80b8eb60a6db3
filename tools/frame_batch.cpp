// Shards of a frame list and the frames already written, for `quadra render
// --shard` and `--skip-existing`.
#include "frame_batch.h"

#include <filesystem>
#include <string>
#include <vector>

#include "cli_options.h"
#include "core/error.h"
#include "sequence_options.h"

namespace quadra {

namespace {

// More shards than any farm runs tasks of one job, and far below int's range.
constexpr int kMaxShards = 1000000;

}  // namespace

Shard parseShard(const std::string& option, const std::string& text) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == text.size())
    throw Error(option + ": '" + text + "' must be I/N (shard I of N, 0 <= I < N)");
  Shard shard;
  shard.count = parseInteger(option, text.substr(slash + 1), 1, kMaxShards);
  shard.index = parseInteger(option, text.substr(0, slash), 0, kMaxShards);
  if (shard.index >= shard.count)
    throw Error(option + ": '" + text + "': shard " + std::to_string(shard.index) +
                " is outside 0.." + std::to_string(shard.count - 1));
  return shard;
}

std::vector<int> shardFrames(const std::vector<int>& frames, const Shard& shard) {
  std::vector<int> mine;
  for (std::size_t p = std::size_t(shard.index); p < frames.size(); p += std::size_t(shard.count))
    mine.push_back(frames[p]);
  return mine;
}

std::vector<std::string> framePaths(const std::vector<std::string>& patterns, int frame) {
  std::vector<std::string> paths;
  for (const std::string& pattern : patterns) paths.push_back(framePath(pattern, frame));
  return paths;
}

bool allFilesExist(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return false;
  }
  return true;
}

}  // namespace quadra
