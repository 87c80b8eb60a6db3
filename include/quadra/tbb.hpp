// Rendering and loading inside the embedder's oneTBB task_arena, for an application that
// already schedules its threads with oneTBB: quadra's parallel loops then run
// on that arena's threads (its max_concurrency is the renderer's thread
// count) instead of an arena of quadra's own. Only this header needs
// oneTBB's headers; quadra/quadra.hpp does not include it.
#pragma once

#include <oneapi/tbb/task_arena.h>

#include <string>

#include "quadra/export.h"
#include "quadra/renderer.hpp"
#include "quadra/scene.hpp"

namespace quadra::api {

// A Renderer whose frames run inside `arena`, which must outlive it. The
// output is the same bits as any other Renderer's.
QUADRA_API Renderer rendererIn(tbb::task_arena& arena);

// load(path, options), its meshes and images decoded on `arena`'s threads:
// the same scene as load's.
QUADRA_API Scene loadIn(const std::string& path, tbb::task_arena& arena,
                        const LoadOptions& options = {});

}  // namespace quadra::api
