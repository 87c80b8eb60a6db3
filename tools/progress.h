// Progress of a `quadra render` sequence on stderr (--progress): a bar that
// redraws itself on a terminal, or one key=value line per frame for logs and
// farm schedulers. Tool code: the engine reports nothing while it renders.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace quadra {

enum class ProgressMode { Bar, Plain, None };

// --progress's default: a bar where stderr is a terminal, else nothing (a
// redrawn bar in a log file is noise; logs ask for plain).
ProgressMode defaultProgressMode();

// Counts the frames of one process's share of a sequence as they finish.
// Frames per second and the ETA count rendered frames only: a skipped frame
// costs a file check, so counting it would promise too early an end.
class SequenceProgress {
 public:
  // `total`: the frames this process was given (its shard, skipped ones included).
  SequenceProgress(ProgressMode mode, int total, std::FILE* stream = stderr);

  // `frame` was rendered in `milliseconds` and written to `paths`.
  void rendered(int frame, const std::vector<std::string>& paths, double milliseconds);
  // `frame` was not rendered: each of `paths` already exists (--skip-existing).
  void skipped(int frame, const std::vector<std::string>& paths);
  // Erases the bar, so that a line on stdout (the same terminal) does not
  // start at its end; the next frame draws it again below that line.
  void clearBar();
  // Ends the bar's line, so that what follows starts on a line of its own.
  void finish();

 private:
  void report(int frame, const char* status, const std::vector<std::string>& paths,
              double milliseconds);

  ProgressMode mode_;
  int total_;
  std::FILE* stream_;
  int done_ = 0;
  int renderedCount_ = 0;
  double renderSeconds_ = 0.0;  // summed over rendered frames
  bool barDrawn_ = false;
};

}  // namespace quadra
