// `quadra env`: an environment's texels as quadra lights with them, written
// to a float EXR, so that outside tools (a reference tracer, another
// renderer) read the same texels: a built-in environment, or a panorama file
// after quadra's decoding and texel rule (docs/lighting.md "Environments").
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cli_options.h"
#include "commands.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "io/image_io.h"
#include "render_options.h"
#include "shading/builtin_environments.h"
#include "shading/environment_source.h"

namespace quadra {
namespace {

constexpr const char* kEnvUsage = R"(usage: quadra env [ENV] --out FILE.exr [--max-memory SIZE]
Writes an environment's texels, exactly as quadra lights with them, to a float EXR.
  ENV                    builtin:NAME or NAME, a built-in environment (default
                         builtin:studio, the one quadra lights with when none is named),
                         or a panorama FILE.hdr|FILE.exr, read as quadra reads it (the
                         texel rule applied: NaN and negative values become 0, values
                         over 2^32 become 2^32)
  --out FILE.exr         where to write the texels: FLOAT R, G, B, ZIP compressed (lossless)
  --max-memory SIZE      what reading the panorama may allocate: bytes or K, M, G, T
                         (1024-based), e.g. 512M (default 8G)
Prints "quadra env source=... width=... height=... nan=... negative=... clamped=..."
(the texel values the rule changed), then "quadra wrote FILE.exr".
built-in environments: )";

std::string envUsage() {
  std::string list;
  for (const std::string& name : builtinEnvironmentNames())
    list += (list.empty() ? "" : ", ") + name;
  return kEnvUsage + list + "\n";
}

struct EnvCommand {
  std::string source = kDefaultEnvironment;
  std::string out;
  LoadOptions load;  // its maxMemory
};

// ENV as loadEnvironment takes it: a bare built-in name gains its prefix
// (unless a file of that name exists); a bare word that is neither a file
// nor a built-in is a mistyped name.
std::string environmentSource(const std::string& argument) {
  if (argument.rfind("builtin:", 0) == 0) return argument;
  std::error_code ec;
  if (std::filesystem::exists(argument, ec)) return argument;
  const std::vector<std::string>& known = builtinEnvironmentNames();
  for (const std::string& name : known)
    if (argument == name) return "builtin:" + name;
  if (argument.find_first_of("./") != std::string::npos) return argument;  // a missing file
  std::string list;
  for (const std::string& name : known) list += (list.empty() ? "" : ", ") + name;
  throw UsageError("env: '" + argument + "' is neither a file nor a built-in environment (" + list +
                   ")" + didYouMean(argument, known));
}

std::optional<EnvCommand> parseEnv(const std::vector<std::string>& args) {
  EnvCommand cmd;
  bool given = false;
  CommandOptions options("env", envUsage());
  options.positional([&](const std::string& argument) {
    if (given) throw Error("env: more than one environment given ('" + argument + "')");
    cmd.source = environmentSource(argument);
    given = true;
  });
  options.text("--out", cmd.out);
  addMaxMemoryOption(options, cmd.load);
  if (options.parse(args) == Parsed::HelpShown) return std::nullopt;
  if (cmd.out.empty()) throw UsageError("env: --out is required");
  if (!endsWithIgnoringCase(cmd.out, ".exr"))
    throw UsageError(cmd.out + ": output must be a .exr file");
  return cmd;
}

}  // namespace

int runEnv(const std::vector<std::string>& args) {
  const std::optional<EnvCommand> parsed = parseEnv(args);
  if (!parsed) return 0;
  const EnvCommand& cmd = *parsed;
  MemoryBudget budget(cmd.load.maxMemory, "env");
  TexelRepairs repairs;
  const EnvironmentImage image = loadEnvironmentArgument(cmd.source, budget, &repairs);
  writeExrRgb(image.rgb.data(), image.width, image.height, cmd.out);
  std::cout << "quadra env source=" << image.name << " width=" << image.width
            << " height=" << image.height << " nan=" << repairs.notANumber
            << " negative=" << repairs.negative << " clamped=" << repairs.clamped << "\n"
            << "quadra wrote " << cmd.out << "\n";
  return 0;
}

}  // namespace quadra
