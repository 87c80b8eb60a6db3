// The one place quadra talks to oneTBB. Everything parallel goes through an
// Executor, so an embedder's task_arena (or a thread count) is a single hook.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>

namespace quadra {

class Executor {
 public:
  // threads <= 0: all cores.
  explicit Executor(int threads = 0);
  ~Executor();
  Executor(const Executor&) = delete;
  Executor& operator=(const Executor&) = delete;

  int threadCount() const { return threads_; }

  // Calls body(begin, end) on disjoint sub-ranges of [0, count) in parallel.
  // grain: the smallest range worth a task. Results must not depend on how
  // the range is split (the determinism rule).
  void parallelFor(std::size_t count, std::size_t grain,
                   const std::function<void(std::size_t, std::size_t)>& body) const;

 private:
  int threads_;
  struct Arena;
  std::unique_ptr<Arena> arena_;
};

}  // namespace quadra
