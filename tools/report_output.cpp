// Whole-file text output and number formatting for the reports.
#include "report_output.h"

#include <unistd.h>

#include <cstdio>
#include <iostream>

#include "core/error.h"

namespace quadra {

void writeText(const std::filesystem::path& path, const std::string& text) {
  const std::string target = path.string(), temporary = target + ".tmp-quadra";
  std::FILE* file = std::fopen(temporary.c_str(), "w");
  if (!file) throw Error(target + ": cannot open for writing");
  const bool ok = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  const bool closed = std::fclose(file) == 0;
  if (!ok || !closed) {
    std::remove(temporary.c_str());
    throw Error(target + ": write failed");
  }
  if (std::rename(temporary.c_str(), target.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw Error(target + ": cannot rename the finished file into place");
  }
}

void progress(const std::string& text) {
  static const bool terminal = ::isatty(STDERR_FILENO) == 1;
  if (terminal) std::cerr << "\r\033[K" << text << std::flush;
}

std::string format(const char* spec, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, spec, value);
  return buffer;
}

std::string figures(double value) {
  return format(value < 10.0 ? "%.2f" : value < 100.0 ? "%.1f" : "%.0f", value);
}

std::string joined(const std::vector<double>& values, const char* spec) {
  std::string text;
  for (const double v : values) {
    if (!text.empty()) text += ';';
    text += format(spec, v);
  }
  return text;
}

}  // namespace quadra
