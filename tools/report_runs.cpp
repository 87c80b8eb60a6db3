// Scenes, the peer, renderer runs and table statistics of the reports that
// time whole processes (report_runs.h).
#include "report_runs.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "cli_options.h"
#include "core/error.h"
#include "lab/scene/builtin_scenes.h"
#include "render_options.h"
#include "subprocess.h"

namespace quadra {

namespace fs = std::filesystem;

fs::path modelFile(const fs::path& assets, const std::string& model) {
  return assets / model / "glTF" / (model + ".gltf");
}

SceneEntry sceneEntryOf(const std::string& entry, const std::string& assets) {
  const std::string prefix = kBuiltinScenePrefix;
  std::error_code ec;
  if (entry.rfind(prefix, 0) == 0) {
    const std::vector<std::string> builtins = builtinSceneNames();
    if (std::find(builtins.begin(), builtins.end(), entry.substr(prefix.size())) == builtins.end())
      throw UsageError("--scenes: unknown built-in scene '" + entry +
                       "' (see quadra render --help)" +
                       didYouMean(entry.substr(prefix.size()), builtins));
    return {entry, entry};
  }
  if ((endsWithIgnoringCase(entry, ".gltf") || endsWithIgnoringCase(entry, ".glb")) &&
      fs::is_regular_file(entry, ec))
    return {fs::path(entry).stem().string(), entry};
  if (fs::is_regular_file(modelFile(assets, entry), ec))
    return {entry, modelFile(assets, entry).string()};
  throw Error("--scenes: '" + entry + "' is neither builtin:NAME, a model in " + assets +
              " nor a .gltf/.glb file");
}

std::optional<fs::path> findLlvmpipePeer() {
  const fs::path peer = executablePath().parent_path() / "quadra-llvmpipe";
  std::error_code ec;
  if (fs::is_regular_file(peer, ec) && ::access(peer.c_str(), X_OK) == 0) return peer;
  return std::nullopt;
}

std::string peerRefusal(const fs::path& peer, const std::vector<std::string>& options) {
  std::vector<std::string> arguments = {
      "render", "builtin:checker-plane", "--width", "8", "--height", "8"};
  arguments.insert(arguments.end(), options.begin(), options.end());
  const ProcessResult probe = runProcess(peer, arguments, fs::temp_directory_path());
  if (probe.exitCode == 0) return {};
  const std::string line = firstLine(probe.err), program = peer.filename().string() + ": ";
  return line.rfind(program, 0) == 0 ? line.substr(program.size()) : line;
}

bool renderAccepts(const fs::path& program, const std::string& option) {
  const ProcessResult help = runProcess(program, {"render", "--help"}, fs::temp_directory_path());
  return help.exitCode == 0 && help.out.find("  " + option + " ") != std::string::npos;
}

std::map<std::string, std::string> runRender(const Contender& contender, const SceneEntry& scene,
                                             const RenderRun& run, const fs::path& output,
                                             const fs::path& scratch, double& seconds) {
  std::vector<std::string> arguments = {"render",    scene.argument,
                                        "--width",   std::to_string(run.width),
                                        "--height",  std::to_string(run.height),
                                        "--threads", std::to_string(run.threads),
                                        "--frames",  std::to_string(run.frames),
                                        "--out",     output.string()};
  arguments.insert(arguments.end(), run.options.begin(), run.options.end());
  arguments.insert(arguments.end(), contender.options.begin(), contender.options.end());
  const ProcessResult result = runProcess(contender.program, arguments, scratch);
  if (result.exitCode != 0)
    throw Error(scene.label + ": " + contender.program.filename().string() +
                " render failed: " + firstLine(result.err));
  const std::map<std::string, std::string> line =
      lineKeyValues(result.out, contender.name + " frame_ms ");
  if (!line.count("median") || !line.count("triangles"))
    throw Error(scene.label + ": " + contender.program.filename().string() +
                " printed no frame_ms line");
  seconds = result.seconds;
  return line;
}

std::string firstLine(const std::string& text) {
  return text.substr(0, text.find('\n'));
}

double medianOf(const std::vector<double>& values) {
  return summarizeFrameTimes(values).median;
}

double geometricMean(const std::vector<double>& values) {
  double sumLog = 0.0;
  for (const double v : values) sumLog += std::log(v);
  return std::exp(sumLog / double(values.size()));
}

std::string withThousands(std::size_t value) {
  std::string digits = std::to_string(value), grouped;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) grouped += ',';
    grouped += digits[i];
  }
  return grouped;
}

std::string fileStem(const std::string& label) {
  std::string stem = label;
  for (char& c : stem)
    if (c == ':' || c == '/' || c == ' ') c = '-';
  return stem;
}

}  // namespace quadra
