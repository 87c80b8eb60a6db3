// Which frames of a sequence one `quadra render` process renders: the frames
// of its shard (--shard I/N) and, with --skip-existing, not those whose
// outputs are already on disk. Works on a list of frame numbers, so any
// sequence (a --sequence range, a turntable's views) is split the same way.
#pragma once

#include <string>
#include <vector>

namespace quadra {

// Shard `index` of `count` (0 <= index < count).
struct Shard {
  int index = 0;
  int count = 1;
};

// "I/N" with 0 <= I < N; anything else is an Error naming `option`.
Shard parseShard(const std::string& option, const std::string& text);

// The frames of `shard`, in their order: the frame at position p of `frames`
// belongs to shard p mod count (round-robin). Every frame belongs to exactly
// one shard; shards differ in size by at most one frame; a shard past the
// end of a short list is empty.
std::vector<int> shardFrames(const std::vector<int>& frames, const Shard& shard);

// Every output path of `frame` (the --out patterns with its number in them).
std::vector<std::string> framePaths(const std::vector<std::string>& patterns, int frame);

// Whether each of `paths` is a regular file. Outputs are written under a
// temporary name and renamed into place (io/image_io.h), so a file under its
// final name is a whole frame; an interrupted write leaves only a temporary.
bool allFilesExist(const std::vector<std::string>& paths);

}  // namespace quadra
