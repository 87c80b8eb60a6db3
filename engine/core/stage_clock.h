// The clock behind FrameStats' stage times: monotonic milliseconds, cheap
// enough (a vDSO read, ~20 ns) to read a few times per front-end chunk and
// per tile without moving the figures it measures.
#pragma once

#include <chrono>

namespace quadra {

inline double stageClockMs() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace quadra
