// The --progress bar and plain lines of `quadra render --sequence`.
#include "progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace quadra {

namespace {

constexpr int kBarWidth = 30;

}  // namespace

ProgressMode defaultProgressMode() {
  return ::isatty(STDERR_FILENO) ? ProgressMode::Bar : ProgressMode::None;
}

SequenceProgress::SequenceProgress(ProgressMode mode, int total, std::FILE* stream)
    : mode_(mode), total_(total), stream_(stream) {}

void SequenceProgress::rendered(int frame, const std::vector<std::string>& paths,
                                double milliseconds) {
  ++renderedCount_;
  renderSeconds_ += milliseconds / 1000.0;
  report(frame, "rendered", paths, milliseconds);
}

void SequenceProgress::skipped(int frame, const std::vector<std::string>& paths) {
  report(frame, "skipped", paths, 0.0);
}

void SequenceProgress::report(int frame, const char* status, const std::vector<std::string>& paths,
                              double milliseconds) {
  ++done_;
  if (mode_ == ProgressMode::None) return;
  const double fps = renderSeconds_ > 0.0 ? renderedCount_ / renderSeconds_ : 0.0;
  const int left = total_ - done_;
  // Unknown (-1) until a frame was rendered; 0 once nothing is left.
  const double etaSeconds = left == 0 ? 0.0 : fps > 0.0 ? left / fps : -1.0;
  if (mode_ == ProgressMode::Plain) {
    std::fprintf(stream_,
                 "quadra progress frame=%d status=%s ms=%.3f done=%d total=%d fps=%.3f "
                 "eta_s=%.1f",
                 frame, status, milliseconds, done_, total_, fps, etaSeconds);
    for (const std::string& path : paths) std::fprintf(stream_, " out=%s", path.c_str());
    std::fputc('\n', stream_);
  } else {
    const int filled = total_ > 0 ? done_ * kBarWidth / total_ : kBarWidth;
    const std::string bar =
        std::string(std::size_t(filled), '#') + std::string(std::size_t(kBarWidth - filled), '.');
    std::string eta = "--";
    if (etaSeconds >= 0.0) {
      const long seconds = std::lround(etaSeconds);
      char text[32];
      std::snprintf(text, sizeof text, "%ld:%02ld", seconds / 60, seconds % 60);
      eta = text;
    }
    // \r and the erase-to-end-of-line escape redraw the bar in place.
    std::fprintf(stream_, "\r[%s] %d/%d frames  %.1f frames/s  ETA %s  frame %d %s\033[K",
                 bar.c_str(), done_, total_, fps, eta.c_str(), frame, status);
    barDrawn_ = true;
  }
  std::fflush(stream_);
}

void SequenceProgress::clearBar() {
  if (barDrawn_) {
    std::fputs("\r\033[K", stream_);
    std::fflush(stream_);
    barDrawn_ = false;
  }
}

void SequenceProgress::finish() {
  if (barDrawn_) {
    std::fputc('\n', stream_);
    std::fflush(stream_);
    barDrawn_ = false;
  }
}

}  // namespace quadra
