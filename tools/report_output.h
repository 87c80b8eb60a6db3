// What the reports share for their output: whole files written at once
// (never a partial file under the requested name) and numbers in printf
// notation for tables.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace quadra {

// Writes through a temporary file and a rename; throws Error naming the file.
void writeText(const std::filesystem::path& path, const std::string& text);

// Overwrites one status line on stderr when it is a terminal; silent
// otherwise, so that stderr stays a one-line error when something fails.
void progress(const std::string& text);

// One number in printf notation, e.g. format("%.3f", x).
std::string format(const char* spec, double value);
// Below 10 two decimals, below 100 one, then none: three figures or more.
std::string figures(double value);
// The values in printf notation, separated by ';' (a list inside one CSV field).
std::string joined(const std::vector<double>& values, const char* spec);

}  // namespace quadra
