// MemoryBudget and the SIZE syntax of --max-memory.
#include "core/memory_budget.h"

#include <cctype>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace quadra {

std::uint64_t parseMemorySize(const std::string& option, const std::string& text) {
  const Error bad = makeError(option, "'" + text +
                                          "' is not a size (bytes, or a number with K, M, G "
                                          "or T, 1024-based: 512M, 4G)");
  std::size_t digits = 0;
  while (digits < text.size() &&
         (std::isdigit(static_cast<unsigned char>(text[digits])) || text[digits] == '.'))
    ++digits;
  if (digits == 0) throw bad;
  // Digits and at most one point only, so strtod sees no sign, exponent or hex.
  const std::string number = text.substr(0, digits);
  if (number.find('.') != number.rfind('.') || number == ".") throw bad;
  const double value = std::strtod(number.c_str(), nullptr);
  std::string unit = text.substr(digits);
  for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
  int shift = 0;
  if (!unit.empty()) {
    const std::string prefixes = "KMGT";
    const std::size_t at = prefixes.find(unit[0]);
    const std::string rest = unit.substr(1);
    if (at == std::string::npos || !(rest.empty() || rest == "B" || rest == "IB")) {
      if (unit != "B") throw bad;
    } else {
      shift = 10 * int(at + 1);
    }
  }
  const double bytes = std::floor(value * std::ldexp(1.0, shift));
  if (!(bytes >= 1.0 && bytes <= std::ldexp(1.0, 50)))
    throw makeError(option, "'" + text + "' is out of range (1 byte to 1024T)");
  return std::uint64_t(bytes);
}

std::string formatBytes(std::uint64_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB"};
  double value = double(bytes) / 1024.0;
  int unit = 0;
  while (value >= 1024.0 && unit < 4) value /= 1024.0, ++unit;
  char text[32];
  std::snprintf(text, sizeof text, "%.1f %s", value, units[unit]);
  return text;
}

MemoryBudget::MemoryBudget(std::uint64_t limit, std::string owner)
    : limit_(limit), owner_(std::move(owner)) {}

void MemoryBudget::charge(const std::string& what, std::uint64_t bytes) {
  if (bytes > limit_ - std::min(used_, limit_))
    throw makeError(owner_, what + " needs " + formatBytes(bytes) + ", over the memory budget of " +
                                formatBytes(limit_) + " (" + formatBytes(used_) +
                                " already used; --max-memory raises it)");
  used_ += bytes;
}

}  // namespace quadra
