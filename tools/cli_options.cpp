// The quadra commands' option parser, strict value parsing, the options they
// share, exit statuses and suggestions.
#include "cli_options.h"

#include <algorithm>
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
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return 2;
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
    throw UsageError(option + ": '" + text + "' is not a number");
  return value;
}

int parseInteger(const std::string& option, const std::string& text, int lo, int hi) {
  const double value = parseNumber(option, text);
  if (value != std::floor(value) || value < lo || value > hi)
    throw UsageError(option + ": '" + text + "' must be a whole number in " + std::to_string(lo) +
                     ".." + std::to_string(hi));
  return int(value);
}

std::vector<std::string> splitList(const std::string& option, const std::string& text) {
  std::vector<std::string> entries;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string entry = text.substr(start, comma - start);
    if (entry.empty()) throw UsageError(option + ": empty entry in '" + text + "'");
    entries.push_back(entry);
    if (comma == std::string::npos) return entries;
    start = comma + 1;
  }
}

int parseSampleCount(const std::string& option, const std::string& text) {
  const double n = parseNumber(option, text);
  if (!(n >= 1 && n <= kMaxSamples) || double(int(n)) != n || !isSampleCount(int(n)))
    throw UsageError(option + ": '" + text + "' must be 1, 2, 4, 8 or 16");
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

// Without leading dashes and case: what a slip is measured on.
std::string comparable(const std::string& name) {
  std::string out = name.substr(std::min(name.find_first_not_of('-'), name.size()));
  for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Optimal string alignment distance: the fewest insertions, deletions,
// substitutions and swaps of neighbours that turn a into b, no substring
// edited twice. The swap counts once because it is the commonest slip of
// fast typing ("smaples").
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

}  // namespace

std::string didYouMean(const std::string& typed, const std::vector<std::string>& known) {
  const std::string slip = comparable(typed);
  if (slip.empty()) return "";
  // A third of the length: one slip in "rendr", two in "smaples", three in
  // "trilinera"; more would match unrelated short names ("mmx" -> "avx2").
  const std::size_t allowed = std::max<std::size_t>(1, std::min<std::size_t>(3, slip.size() / 3));
  std::size_t best = allowed + 1;
  std::vector<std::string> closest;
  for (const std::string& name : known) {
    const std::string candidate = comparable(name);
    const std::size_t distance = slip.size() >= 2 && candidate.rfind(slip, 0) == 0
                                     ? 0  // a prefix outranks any slip
                                     : editDistance(slip, candidate);
    if (distance > allowed) continue;
    if (distance < best) {
      best = distance;
      closest.clear();
    }
    if (distance == best && closest.size() < 3) closest.push_back(name);
  }
  if (closest.empty()) return "";
  std::string names;
  for (std::size_t i = 0; i < closest.size(); ++i)
    names += (i == 0 ? "" : i + 1 == closest.size() ? " or " : ", ") + closest[i];
  return " (did you mean " + names + "?)";
}

std::string didYouMean(const std::string& typed, const std::string& knownList) {
  std::vector<std::string> known;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = knownList.find(',', start);
    const std::size_t first = knownList.find_first_not_of(' ', start);
    if (first != std::string::npos && first < comma)
      known.push_back(knownList.substr(first, comma - first));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return didYouMean(typed, known);
}

std::string summaryLines(const std::vector<std::pair<std::string, std::string>>& rows) {
  std::size_t width = 0;
  for (const auto& row : rows) width = std::max(width, row.first.size());
  std::string lines;
  for (const auto& [name, summary] : rows)
    lines += "  " + name + std::string(width - name.size() + 3, ' ') + summary + "\n";
  return lines;
}

CommandOptions::CommandOptions(std::string command, std::string usage, std::string program)
    : command_(std::move(command)), usage_(std::move(usage)), program_(std::move(program)) {}

void CommandOptions::declare(const std::string& name, bool takesValue, bool checksFiles,
                             ValueHandler handler) {
  QUADRA_CHECK(isOptionName(name) && !find(name));
  options_.push_back({name, {takesValue, checksFiles, std::move(handler)}});
}

void CommandOptions::value(const std::string& name, ValueHandler handler) {
  declare(name, true, false, std::move(handler));
}

void CommandOptions::pathValue(const std::string& name, ValueHandler handler) {
  declare(name, true, true, std::move(handler));
}

void CommandOptions::flag(const std::string& name, std::function<void()> handler) {
  declare(name, false, false,
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
  throw UsageError(option + ": unknown " + what + " '" + text + "' (" + list + ")" +
                   didYouMean(text, spellings));
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
  for (const std::string& arg : args) {
    if (!isOptionName(arg) || find(arg)) continue;
    // A suggestion takes the place of the pointer to --help: it is the more
    // likely fix, and the line stays short.
    std::vector<std::string> names;
    for (const auto& declared : options_) names.push_back(declared.first);
    const std::string suggestion = didYouMean(arg, names);
    throw UsageError(command_ + ": unknown option '" + arg +
                     (suggestion.empty() ? seeHelp : "'" + suggestion));
  }

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
      if (!positional_) throw UsageError(command_ + ": unexpected argument '" + arg + seeHelp);
      steps.push_back({nullptr, arg, nullptr});
      continue;
    }
    const Option* option = find(arg);
    const std::string* value = nullptr;
    if (option->takesValue) {
      if (i + 1 >= args.size() || isOptionName(args[i + 1]))
        throw UsageError(arg + ": missing value");
      value = &args[++i];
    }
    steps.push_back({option, arg, value});
  }
  static const std::string noValue;
  for (const Step& step : steps) {
    try {
      if (step.option)
        step.option->handler(step.argument, step.value ? *step.value : noValue);
      else
        positional_(step.argument);
    } catch (const UsageError&) {
      throw;
    } catch (const Error& e) {
      if (step.option && step.option->checksFiles) throw;
      throw UsageError(e.what());
    }
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
      throw UsageError(option + ": unknown filter '" + text + "' (" + filterNames() + ")" +
                       didYouMean(text, filterNames()));
    filter = parsed;
  });
  addAnisoOption(options, maxAniso);
  options.value("--lod-bias", [&lodBias](const std::string& option, const std::string& text) {
    lodBias = float(parseNumber(option, text));
    if (std::fabs(lodBias) > 32.0f) throw UsageError(option + ": must lie in -32..32");
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
    const std::string names = "auto, scalar, sse2, avx2, avx512";
    if (!isa)
      throw UsageError(option + ": unknown ISA '" + text + "' (" + names + ")" +
                       didYouMean(text, names));
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
  const std::string names = alternatives + "rgba32f, rgba16f, rgba8, rgba8srgb";
  if (!parseFormat(text, format))
    throw UsageError(option + ": unknown texel format '" + text + "' (" + names + ")" +
                     didYouMean(text, names));
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
