// The one place quadra talks to oneTBB. Everything parallel goes through an
// Executor, so an embedder's task_arena (or a thread count) is a single hook.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>

// oneTBB's task_arena, declared where oneTBB 2021 declares it so this
// header need not include oneTBB (parallel.cpp checks it is the same class).
namespace tbb::detail::d1 {
class task_arena;
}

namespace quadra {

using TaskArena = tbb::detail::d1::task_arena;

class Executor {
 public:
  // threads <= 0: all cores.
  explicit Executor(int threads = 0);
  // Runs every parallel loop inside the embedder's arena, which must outlive
  // the executor; its concurrency is the thread count.
  explicit Executor(TaskArena& external);
  ~Executor();
  Executor(const Executor&) = delete;
  Executor& operator=(const Executor&) = delete;

  int threadCount() const { return threads_; }

  // Calls body(begin, end) on disjoint sub-ranges of [0, count) in parallel.
  // grain: the smallest range worth a task. Results must not depend on how
  // the range is split (the determinism rule).
  void parallelFor(std::size_t count, std::size_t grain,
                   const std::function<void(std::size_t, std::size_t)>& body) const;

  // Inside a parallelFor body: the running thread's index in
  // [0, threadCount()). No two bodies running at once share one, so scratch
  // kept per index serves every sub-range a thread takes, where scratch made
  // per sub-range is allocated, faulted in and unmapped (TLB shootdowns
  // across the threads) tens of times a loop. Not for a body that runs a
  // parallel loop itself: while it waits, its thread may run another body.
  int workerIndex() const;

 private:
  int threads_;
  struct Arena;
  std::unique_ptr<Arena> arena_;
};

}  // namespace quadra
