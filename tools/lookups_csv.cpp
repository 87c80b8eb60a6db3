// The lookups CSV of `quadra sample`: header check, then six numbers a row.
#include "lookups_csv.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace quadra {
namespace {

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

}  // namespace

Lookups readLookups(std::istream& in, const std::string& source) {
  std::string line;
  if (!std::getline(in, line))
    throw Error(source + ": empty file (expected header u,v,dudx,dvdx,dudy,dvdy)");
  std::string header = trim(line);
  if (!header.empty() && static_cast<unsigned char>(header[0]) == 0xEF && header.size() >= 3)
    header = header.substr(3);  // UTF-8 byte order mark
  header.erase(std::remove(header.begin(), header.end(), ' '), header.end());
  if (header != "u,v,dudx,dvdx,dudy,dvdy")
    throw Error(source + ": line 1: header must be u,v,dudx,dvdx,dudy,dvdy");
  Lookups lookups;
  for (std::size_t lineNumber = 2; std::getline(in, line); ++lineNumber) {
    const std::string row = trim(line);
    if (row.empty()) continue;
    std::stringstream fields(row);
    std::string field;
    int n = 0;
    while (std::getline(fields, field, ',')) {
      if (n == 6)
        throw Error(source + ": line " + std::to_string(lineNumber) + ": more than 6 fields");
      char* end = nullptr;
      const std::string text = trim(field);
      const float value = std::strtof(text.c_str(), &end);
      if (text.empty() || *end != '\0')
        throw Error(source + ": line " + std::to_string(lineNumber) + ": '" + text +
                    "' is not a number");
      lookups.column[n++].push_back(value);
    }
    if (n != 6)
      throw Error(source + ": line " + std::to_string(lineNumber) + ": expected 6 fields, found " +
                  std::to_string(n));
  }
  return lookups;
}

Lookups readLookups(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw Error(path + ": cannot open for reading");
  return readLookups(file, path);
}

}  // namespace quadra
