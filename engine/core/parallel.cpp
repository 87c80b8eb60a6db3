// Executor on a private tbb::task_arena sized to the requested thread count,
// or on one the embedder passes.
#include "core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <optional>
#include <type_traits>

namespace quadra {

static_assert(std::is_same_v<TaskArena, tbb::task_arena>,
              "core/parallel.h's declaration of tbb::task_arena is not oneTBB's");

// A private arena of `threads` threads, or the embedder's.
struct Executor::Arena {
  explicit Arena(int threads) : own(std::in_place, threads), arena(*own) {
    // TBB caps its worker pool at the machine's cores (and warns when an arena
    // asks for more); a caller asking for more threads than cores, e.g. to
    // show that results do not depend on the split, gets them while this
    // executor lives. A lower cap the embedder set stays in force.
    if (threads > tbb::info::default_concurrency())
      allowThreads.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  }
  explicit Arena(tbb::task_arena& external) : arena(external) {}
  std::optional<tbb::global_control> allowThreads;  // outlives the arena
  std::optional<tbb::task_arena> own;
  tbb::task_arena& arena;
};

Executor::Executor(int threads)
    : threads_(threads > 0 ? threads : tbb::this_task_arena::max_concurrency()),
      arena_(std::make_unique<Arena>(threads_)) {}

Executor::Executor(TaskArena& external)
    : threads_(external.max_concurrency()), arena_(std::make_unique<Arena>(external)) {}

Executor::~Executor() = default;

void Executor::parallelFor(std::size_t count, std::size_t grain,
                           const std::function<void(std::size_t, std::size_t)>& body) const {
  if (count == 0) return;
  if (threads_ == 1 || count <= grain) {
    body(0, count);
    return;
  }
  arena_->arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain),
                      [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
  });
}

int Executor::workerIndex() const {
  // One thread runs the body where parallelFor does not enter the arena
  // (one thread, or a single sub-range), and it may be outside any arena.
  const int index = tbb::this_task_arena::current_thread_index();
  return index >= 0 && index < threads_ ? index : 0;
}

}  // namespace quadra
