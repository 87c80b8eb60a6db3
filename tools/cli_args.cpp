// Strict option-value parsing for the command-line tool.
#include "cli_args.h"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace quadra {

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

bool endsWithIgnoringCase(const std::string& text, const std::string& suffix) {
  if (text.size() < suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(text[text.size() - suffix.size() + i])) !=
        std::tolower(static_cast<unsigned char>(suffix[i])))
      return false;
  return true;
}

}  // namespace quadra
