// The embedder's threads (issue 15): loading on a tbb::task_arena the
// embedder passes (LoadOptions::arena; rendering on one is
// PublicApi.RendererInTheEmbeddersArenaRunsThereWithTheSameBits), seen from
// an observer on that arena, with the same scene as on quadra's own; and
// several Renderers rendering at once in one process (the sanitizer suites
// run this under TSan). And the executor's worker index, which per-worker
// scratch relies on, on its own arena and on the embedder's.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>
#include <tbb/task_scheduler_observer.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "api/renderer.h"
#include "core/parallel.h"
#include "lab/scene/builtin_scenes.h"
#include "render_helpers.h"
#include "scene/gltf_loader.h"

namespace quadra {
namespace {

// Counts the threads that enter one arena: none when the work ran elsewhere.
class ArenaEntries : public tbb::task_scheduler_observer {
 public:
  explicit ArenaEntries(tbb::task_arena& arena) : tbb::task_scheduler_observer(arena) {
    observe(true);
  }
  ~ArenaEntries() override { observe(false); }
  void on_scheduler_entry(bool) override { ++entries; }
  std::atomic<int> entries{0};
};

RenderSettings smallFrame() {
  RenderSettings settings;
  settings.width = 192;
  settings.height = 108;
  settings.samples = 4;
  return settings;
}

TEST(EmbedderThreads, LoadsOnTheEmbeddersArenaWithTheSameScene) {
  const std::string path =
      std::string(QUADRA_ASSETS_DIR) + "/BoomBoxWithAxes/glTF/BoomBoxWithAxes.gltf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "sample model absent: " << path;
  const Scene own = loadGltf(path);
  tbb::task_arena arena(2);
  ArenaEntries entries(arena);
  LoadOptions options;
  options.arena = &arena;
  const Scene scene = loadGltf(path, options);
  EXPECT_GT(entries.entries.load(), 0) << "nothing ran on the embedder's arena";
  ASSERT_EQ(scene.meshes.size(), own.meshes.size());
  for (std::size_t m = 0; m < own.meshes.size(); ++m) {
    EXPECT_EQ(scene.meshes[m].positions, own.meshes[m].positions);
    EXPECT_EQ(scene.meshes[m].indices, own.meshes[m].indices);
  }
  ASSERT_EQ(scene.textures.size(), own.textures.size());
  for (std::size_t t = 0; t < own.textures.size(); ++t)
    EXPECT_EQ(scene.textures[t]->image().rgba, own.textures[t]->image().rgba);
  // One thread: decoded on the loading thread alone, the same scene.
  const Scene serial = loadGltf(path, {.threads = 1});
  ASSERT_EQ(serial.textures.size(), own.textures.size());
  for (std::size_t t = 0; t < own.textures.size(); ++t)
    EXPECT_EQ(serial.textures[t]->image().rgba, own.textures[t]->image().rgba);
}

// No global state: Renderers on several threads at once, each frame the
// bits it has alone.
TEST(EmbedderThreads, SeveralRenderersRenderAtOnce) {
  const std::vector<std::string> names = {"showcase", "alpha-quads", "checker-plane"};
  std::vector<Scene> scenes;
  std::vector<Frame> alone;
  for (const std::string& name : names) {
    scenes.push_back(makeBuiltinScene(name));
    alone.push_back(renderOnce(scenes.back(), firstCameraOrDefault(scenes.back()), smallFrame()));
  }
  std::vector<Frame> together(names.size());
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < names.size(); ++i)
    threads.emplace_back([&, i] {
      RendererConfig config;
      config.threads = 2;
      Renderer renderer(config);
      for (int round = 0; round < 2; ++round)
        renderer.render(scenes[i], firstCameraOrDefault(scenes[i]), smallFrame(), together[i]);
    });
  for (std::thread& thread : threads) thread.join();
  for (std::size_t i = 0; i < names.size(); ++i) {
    EXPECT_EQ(together[i].rgba, alone[i].rgba) << names[i];
    EXPECT_EQ(together[i].depth, alone[i].depth) << names[i];
  }
}

// Every body of a loop sees an index in [0, threadCount()) that no other
// body running at the same time holds: each body marks its index busy
// while it runs, long enough for the threads to overlap.
void expectWorkerIndicesExclusive(const Executor& executor) {
  std::vector<std::atomic<int>> busy(std::size_t(executor.threadCount()));
  std::atomic<int> outOfRange{0}, shared{0}, bodies{0};
  executor.parallelFor(256, 1, [&](std::size_t, std::size_t) {
    ++bodies;
    const int index = executor.workerIndex();
    if (index < 0 || index >= executor.threadCount()) {
      ++outOfRange;
      return;
    }
    if (busy[std::size_t(index)].exchange(1) != 0) ++shared;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    busy[std::size_t(index)] = 0;
  });
  EXPECT_GT(bodies.load(), 1) << "the loop was not split";
  EXPECT_EQ(outOfRange.load(), 0);
  EXPECT_EQ(shared.load(), 0) << "two bodies ran at once with one index";
  // Not asserted: that several threads took part. Where other work holds
  // TBB's workers (a test process of many tests), one thread may run them all.
}

TEST(EmbedderThreads, WorkerIndicesAreExclusiveOnOwnAndEmbeddersArena) {
  expectWorkerIndicesExclusive(Executor(3));
  tbb::task_arena arena(3);
  expectWorkerIndicesExclusive(Executor(arena));
  const Executor one(1);
  one.parallelFor(8, 1, [&](std::size_t, std::size_t) { EXPECT_EQ(one.workerIndex(), 0); });
}

}  // namespace
}  // namespace quadra
