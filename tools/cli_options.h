// The one option parser of the quadra commands, and the options several
// commands share (filtering, threads, ISA, texel formats, seed), so that each
// option's name, range and error message exist once; the usage errors and
// exit statuses of the quadra programs, and the "did you mean" suggestions
// their messages end with. Every failure is an Error naming the option or
// the command.
#pragma once

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "simd/isa.h"
#include "texture/sampler_state.h"
#include "texture/texel_format.h"

namespace quadra {

// A command line wrong in itself, whatever the files it names and the
// machine it runs on: an unknown command, subject or option, a missing or
// malformed value, options that do not combine. runMain exits 2 for it and 1
// for any other failure, so a script tells a command it got wrong from a run
// that failed. Tools-side: the engine's own errors are all about its input.
class UsageError : public Error {
 public:
  using Error::Error;
};

// " (did you mean X?)" naming the entries of `known` closest to `typed`, for
// the end of the message that calls `typed` unknown; "" when none is close.
// Close: `typed` starts it (at least two characters), or it is a few slips
// away (optimal string alignment distance, at most a third of `typed`'s
// length and at least 1: "--smaples" -> --samples, "rendr" -> render), both
// without case and leading dashes. Ties are all named, up to three.
std::string didYouMean(const std::string& typed, const std::vector<std::string>& known);
// The same with `known` as the messages list it: "a, b, c".
std::string didYouMean(const std::string& typed, const std::string& knownList);

// The lines of an overview: each name, padded to one column, then its
// summary, indented by two spaces.
std::string summaryLines(const std::vector<std::pair<std::string, std::string>>& rows);

// These parse an option's value: their Errors are UsageErrors.
double parseNumber(const std::string& option, const std::string& text);
int parseInteger(const std::string& option, const std::string& text, int lo, int hi);
bool endsWithIgnoringCase(const std::string& text, const std::string& suffix);
// The entries of a comma-separated list, in order; an Error naming the
// option for an empty entry.
std::vector<std::string> splitList(const std::string& option, const std::string& text);
// A sample count the engine renders: 1, 2, 4, 8 or 16.
int parseSampleCount(const std::string& option, const std::string& text);

// main()'s body for a quadra program: returns run(args)'s status, and turns
// any failure into one line on stderr, "program: message", and status 2 for a
// UsageError, 1 for any other.
int runMain(const char* program, int argc, char** argv,
            const std::function<int(const std::vector<std::string>& args)>& run);

enum class Parsed : std::uint8_t { Run, HelpShown };

// One command's options. Declare them, then parse: handlers run in
// command-line order, but only once the whole line is well formed, so an
// unknown option or a missing value is named as such wherever it stands
// instead of surfacing as some other option's bad value. An argument starting
// with "--" is always an option name, never a value.
class CommandOptions {
 public:
  using ValueHandler = std::function<void(const std::string& option, const std::string& value)>;
  using PositionalHandler = std::function<void(const std::string& argument)>;

  // `command` as typed after the program's name (e.g. "report textures"), for
  // messages; `usage` is what --help and -h print; `program` is the binary
  // (a peer renderer has its own).
  CommandOptions(std::string command, std::string usage, std::string program = "quadra");

  // A handler's Error is a UsageError: a handler reads a value, and a value
  // it refuses is the command line's fault.
  void value(const std::string& name, ValueHandler handler);
  // A value the handler checks against the file system (a folder that must
  // exist): its Error stays an input error, exit 1, as a missing file's is.
  void pathValue(const std::string& name, ValueHandler handler);
  void flag(const std::string& name, std::function<void()> handler);
  // Arguments that are not options; a command without this handler takes none.
  void positional(PositionalHandler handler);

  void integer(const std::string& name, int& target, int lo, int hi);
  void text(const std::string& name, std::string& target);
  // One of `names`, each standing for a value; `what` names the kind in the
  // error ("depth mode").
  template <typename T>
  void choice(const std::string& name, const std::string& what,
              std::initializer_list<std::pair<const char*, T>> names, T& target) {
    const std::vector<std::pair<const char*, T>> known(names);
    value(name, [known, what, &target](const std::string& option, const std::string& text) {
      std::vector<std::string> spellings;
      for (const auto& [spelling, meaning] : known) {
        if (text == spelling) {
          target = meaning;
          return;
        }
        spellings.push_back(spelling);
      }
      throwUnknownChoice(option, what, text, spellings);
    });
  }

  // Precedence: --help or -h anywhere, then an undeclared "--" option
  // anywhere (with the declared ones closest to it), then the first missing
  // value or unexpected argument, then the handlers' own errors in
  // command-line order.
  Parsed parse(const std::vector<std::string>& args) const;

 private:
  struct Option {
    bool takesValue = false;
    bool checksFiles = false;  // pathValue
    ValueHandler handler;      // flags ignore the value
  };
  [[noreturn]] static void throwUnknownChoice(const std::string& option, const std::string& what,
                                              const std::string& text,
                                              const std::vector<std::string>& spellings);
  void declare(const std::string& name, bool takesValue, bool checksFiles, ValueHandler handler);
  const Option* find(const std::string& name) const;

  std::string command_, usage_, program_;
  std::vector<std::pair<std::string, Option>> options_;
  PositionalHandler positional_;
};

// The filter group: --filter, --aniso and --lod-bias (within -32..32).
void addFilterOptions(CommandOptions& options, std::optional<Filter>& filter, int& maxAniso,
                      float& lodBias);
// --aniso alone, for a command that measures every filter.
void addAnisoOption(CommandOptions& options, int& maxAniso);
// --min-lod and --max-lod; the command checks 0 <= min <= max once all are parsed.
void addLodRangeOptions(CommandOptions& options, float& minLod, float& maxLod);

void addThreadsOption(CommandOptions& options, int& threads);
// --samples N: one of the sample counts parseSampleCount takes.
void addSamplesOption(CommandOptions& options, int& samples);
// auto (nullopt: the best the CPU has) or a path by name.
void addIsaOption(CommandOptions& options, std::optional<Isa>& isa);
// The requested path, or the best the CPU has; an Error when the CPU lacks it.
Isa supportedIsa(const std::optional<Isa>& requested);
void addSeedOption(CommandOptions& options, std::uint64_t& seed);

void addTexelFormatOption(CommandOptions& options, const std::string& name, TexelFormat& format);
// Also "auto" (nullopt: the command's own choice of storage).
void addTexelFormatOrAutoOption(CommandOptions& options, const std::string& name,
                                std::optional<TexelFormat>& format);

}  // namespace quadra
