// Option-value parsing shared by the quadra commands: strict numbers, with a
// one-line Error naming the option on anything else.
#pragma once

#include <string>
#include <vector>

namespace quadra {

double parseNumber(const std::string& option, const std::string& text);
int parseInteger(const std::string& option, const std::string& text, int lo, int hi);
bool endsWithIgnoringCase(const std::string& text, const std::string& suffix);

int runSample(int argc, const char* const* argv);
int runReport(int argc, const char* const* argv);
// `quadra report sat-precision` (report_sat_precision.cpp); args after the subject.
int runSatPrecisionReport(const std::vector<std::string>& args);
// `quadra report stability` (report_stability.cpp); args after the subject.
int runStabilityReport(const std::vector<std::string>& args);

}  // namespace quadra
