// The quadra commands behind the entry point (quadra_main.cpp), each given
// the arguments after its own name.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace quadra {

// The report subjects in the order the overviews list them, each with one
// line on what it measures (`quadra help`, `quadra report --help`).
std::vector<std::pair<std::string, std::string>> reportSubjects();

// `quadra sample` (sample_command.cpp).
int runSample(const std::vector<std::string>& args);
// `quadra env` (env_command.cpp).
int runEnv(const std::vector<std::string>& args);
// `quadra report SUBJECT` (report_command.cpp); args start with the subject.
int runReport(const std::vector<std::string>& args);
// `quadra report sat-precision` (report_sat_precision.cpp).
int runSatPrecisionReport(const std::vector<std::string>& args);
// `quadra report frames` (report_frames.cpp).
int runFramesReport(const std::vector<std::string>& args);
// `quadra report stability` (report_stability.cpp).
int runStabilityReport(const std::vector<std::string>& args);
// `quadra report samples` (report_samples.cpp).
int runSamplesReport(const std::vector<std::string>& args);

}  // namespace quadra
