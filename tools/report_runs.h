// What the reports that time whole renderer processes share (`quadra report
// frames`, `quadra report lighting`): naming their scenes, finding the
// llvmpipe peer beside quadra, running one `render` of a renderer and reading
// its frame_ms line back, and the statistics of their tables.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace quadra {

// One scene of a report: what the table calls it and what `render` is given.
struct SceneEntry {
  std::string label;     // builtin:NAME, a model's name, or a file's stem
  std::string argument;  // builtin:NAME or a file path
};

// DIR/<Model>/glTF/<Model>.gltf, the sample models' layout.
std::filesystem::path modelFile(const std::filesystem::path& assets, const std::string& model);

// One --scenes entry: builtin:NAME (a known built-in scene), a .gltf/.glb
// file, or the name of a model in `assets`; a UsageError or Error naming
// the entry otherwise.
SceneEntry sceneEntryOf(const std::string& entry, const std::string& assets);

// A renderer under test: its name is the frame_ms line's first word.
struct Contender {
  std::string name;
  std::filesystem::path program;
  std::vector<std::string> options;  // its own, after the shared ones
};

// quadra-llvmpipe beside the running program (tools/peer/), where it was built.
std::optional<std::filesystem::path> findLlvmpipePeer();

// What the peer says to an 8x8 frame of builtin:checker-plane with
// `options`: empty when it draws it, else its error's first line less the
// program's name (asked before a report writes anything).
std::string peerRefusal(const std::filesystem::path& peer, const std::vector<std::string>& options);
// Whether `program render --help` lists `option` (a peer built before the
// option was).
bool renderAccepts(const std::filesystem::path& program, const std::string& option);

// What every renderer of one run is given: `render SCENE --width W --height
// H --threads N --frames K --out FILE`, then `options`, then the
// contender's own.
struct RenderRun {
  int width = 0, height = 0, threads = 1, frames = 1;
  std::vector<std::string> options;
};

// Runs `contender render SCENE … --out output` (stdout and stderr through
// files in `scratch`) and returns its frame_ms line's key=value pairs, with
// the run's wall time from spawn to exit in `seconds`; an Error names the
// scene, the renderer and the renderer's own first line when it fails.
std::map<std::string, std::string> runRender(const Contender& contender, const SceneEntry& scene,
                                             const RenderRun& run,
                                             const std::filesystem::path& output,
                                             const std::filesystem::path& scratch, double& seconds);

std::string firstLine(const std::string& text);
// The median of one figure's values over the rounds (not empty).
double medianOf(const std::vector<double>& values);
double geometricMean(const std::vector<double>& values);
// 16688 -> "16,688".
std::string withThousands(std::size_t value);
// A label made fit for a file name (':', '/' and ' ' become '-').
std::string fileStem(const std::string& label);

}  // namespace quadra
