// The quadra commands' option parser, strict value parsing, and the options
// they share.
#include "cli_options.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <new>

#include "core/error.h"
#include "window/sample_pattern.h"

namespace quadra {

int runMain(const char* program, int argc, char** argv,
            const std::function<int(const std::vector<std::string>& args)>& run) {
  try {
    return run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "%s: out of memory\n", program);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
  }
  return 1;
}

double parseNumber(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0])) || *end != '\0' ||
      !std::isfinite(value))
    throw Error(option + ": '" + text + "' is not a number");
  return value;
}

int parseInteger(const std::string& option, const std::string& text, int lo, int hi) {
  const double value = parseNumber(option, text);
  if (value != std::floor(value) || value < lo || value > hi)
    throw Error(option + ": '" + text + "' must be a whole number in " + std::to_string(lo) + ".." +
                std::to_string(hi));
  return int(value);
}

std::vector<std::string> splitList(const std::string& option, const std::string& text) {
  std::vector<std::string> entries;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string entry = text.substr(start, comma - start);
    if (entry.empty()) throw Error(option + ": empty entry in '" + text + "'");
    entries.push_back(entry);
    if (comma == std::string::npos) return entries;
    start = comma + 1;
  }
}

int parseSampleCount(const std::string& option, const std::string& text) {
  const double n = parseNumber(option, text);
  if (!(n >= 1 && n <= kMaxSamples) || double(int(n)) != n || !isSampleCount(int(n)))
    throw Error(option + ": '" + text + "' must be 1, 2, 4, 8 or 16");
  return int(n);
}

bool endsWithIgnoringCase(const std::string& text, const std::string& suffix) {
  if (text.size() < suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(text[text.size() - suffix.size() + i])) !=
        std::tolower(static_cast<unsigned char>(suffix[i])))
      return false;
  return true;
}

namespace {

bool isOptionName(const std::string& arg) {
  return arg.rfind("--", 0) == 0;
}

}  // namespace

CommandOptions::CommandOptions(std::string command, std::string usage, std::string program)
    : command_(std::move(command)), usage_(std::move(usage)), program_(std::move(program)) {}

void CommandOptions::declare(const std::string& name, bool takesValue, ValueHandler handler) {
  QUADRA_CHECK(isOptionName(name) && !find(name));
  options_.push_back({name, {takesValue, std::move(handler)}});
}

void CommandOptions::value(const std::string& name, ValueHandler handler) {
  declare(name, true, std::move(handler));
}

void CommandOptions::flag(const std::string& name, std::function<void()> handler) {
  declare(name, false,
          [handler = std::move(handler)](const std::string&, const std::string&) { handler(); });
}

void CommandOptions::positional(PositionalHandler handler) {
  positional_ = std::move(handler);
}

void CommandOptions::integer(const std::string& name, int& target, int lo, int hi) {
  value(name, [&target, lo, hi](const std::string& option, const std::string& text) {
    target = parseInteger(option, text, lo, hi);
  });
}

void CommandOptions::text(const std::string& name, std::string& target) {
  value(name, [&target](const std::string&, const std::string& text) { target = text; });
}

void CommandOptions::throwUnknownChoice(const std::string& option, const std::string& what,
                                        const std::string& text,
                                        const std::vector<std::string>& spellings) {
  std::string list;
  for (const std::string& spelling : spellings) list += (list.empty() ? "" : ", ") + spelling;
  throw Error(option + ": unknown " + what + " '" + text + "' (" + list + ")");
}

const CommandOptions::Option* CommandOptions::find(const std::string& name) const {
  for (const auto& [declared, option] : options_)
    if (declared == name) return &option;
  return nullptr;
}

Parsed CommandOptions::parse(const std::vector<std::string>& args) const {
  for (const std::string& arg : args)
    if (arg == "--help" || arg == "-h") {
      std::cout << usage_;
      return Parsed::HelpShown;
    }
  const std::string seeHelp = "' (see " + program_ + " " + command_ + " --help)";
  for (const std::string& arg : args)
    if (isOptionName(arg) && !find(arg))
      throw Error(command_ + ": unknown option '" + arg + seeHelp);

  // The whole command line is checked before any handler runs.
  struct Step {
    const Option* option;  // null: a positional argument
    const std::string& argument;
    const std::string* value;
  };
  std::vector<Step> steps;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (!isOptionName(arg)) {
      if (!positional_) throw Error(command_ + ": unexpected argument '" + arg + seeHelp);
      steps.push_back({nullptr, arg, nullptr});
      continue;
    }
    const Option* option = find(arg);
    const std::string* value = nullptr;
    if (option->takesValue) {
      if (i + 1 >= args.size() || isOptionName(args[i + 1])) throw Error(arg + ": missing value");
      value = &args[++i];
    }
    steps.push_back({option, arg, value});
  }
  static const std::string noValue;
  for (const Step& step : steps) {
    if (step.option)
      step.option->handler(step.argument, step.value ? *step.value : noValue);
    else
      positional_(step.argument);
  }
  return Parsed::Run;
}

void addAnisoOption(CommandOptions& options, int& maxAniso) {
  options.integer("--aniso", maxAniso, 1, 64);
}

void addFilterOptions(CommandOptions& options, std::optional<Filter>& filter, int& maxAniso,
                      float& lodBias) {
  options.value("--filter", [&filter](const std::string& option, const std::string& text) {
    Filter parsed;
    if (!parseFilter(text, parsed))
      throw Error(option + ": unknown filter '" + text + "' (" + filterNames() + ")");
    filter = parsed;
  });
  addAnisoOption(options, maxAniso);
  options.value("--lod-bias", [&lodBias](const std::string& option, const std::string& text) {
    lodBias = float(parseNumber(option, text));
    if (std::fabs(lodBias) > 32.0f) throw Error(option + ": must lie in -32..32");
  });
}

void addLodRangeOptions(CommandOptions& options, float& minLod, float& maxLod) {
  // A named pointer, not a structured binding: clang 14, which builds the
  // ASan suite, cannot capture a binding.
  for (const auto& bound : {std::pair{"--min-lod", &minLod}, std::pair{"--max-lod", &maxLod}}) {
    float* target = bound.second;
    options.value(bound.first, [target](const std::string& option, const std::string& text) {
      *target = float(parseNumber(option, text));
    });
  }
}

void addThreadsOption(CommandOptions& options, int& threads) {
  options.integer("--threads", threads, 1, 1024);
}

void addSamplesOption(CommandOptions& options, int& samples) {
  options.value("--samples", [&samples](const std::string& option, const std::string& value) {
    samples = parseSampleCount(option, value);
  });
}

void addIsaOption(CommandOptions& options, std::optional<Isa>& isa) {
  options.value("--isa", [&isa](const std::string& option, const std::string& text) {
    if (text == "auto") {
      isa.reset();
      return;
    }
    isa = parseIsa(text);
    if (!isa)
      throw Error(option + ": unknown ISA '" + text + "' (auto, scalar, sse2, avx2, avx512)");
  });
}

Isa supportedIsa(const std::optional<Isa>& requested) {
  const Isa isa = requested.value_or(detectBestIsa());
  if (!isaSupported(isa))
    throw Error(std::string("--isa ") + isaName(isa) + ": this CPU does not support it");
  return isa;
}

void addSeedOption(CommandOptions& options, std::uint64_t& seed) {
  options.value("--seed", [&seed](const std::string& option, const std::string& text) {
    seed = std::uint64_t(parseInteger(option, text, 0, 2147483647));
  });
}

namespace {

// `alternatives` lists what else the option accepts, for the message.
TexelFormat parseTexelFormat(const std::string& option, const std::string& text,
                             const std::string& alternatives) {
  TexelFormat format;
  if (!parseFormat(text, format))
    throw Error(option + ": unknown texel format '" + text + "' (" + alternatives +
                "rgba32f, rgba16f, rgba8, rgba8srgb)");
  return format;
}

}  // namespace

void addTexelFormatOption(CommandOptions& options, const std::string& name, TexelFormat& format) {
  options.value(name, [&format](const std::string& option, const std::string& text) {
    format = parseTexelFormat(option, text, "");
  });
}

void addTexelFormatOrAutoOption(CommandOptions& options, const std::string& name,
                                std::optional<TexelFormat>& format) {
  options.value(name, [&format](const std::string& option, const std::string& text) {
    if (text == "auto")
      format.reset();
    else
      format = parseTexelFormat(option, text, "auto, ");
  });
}

}  // namespace quadra
