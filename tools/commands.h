// The quadra commands behind the entry points, each given the arguments after
// its own name: `sample` in quadra (quadra_main.cpp), the reports in
// quadra-report (report_command.cpp), which `quadra report` runs.
#pragma once

#include <string>
#include <vector>

namespace quadra {

// `quadra sample` (sample_command.cpp).
int runSample(const std::vector<std::string>& args);
// `quadra env` (env_command.cpp).
int runEnv(const std::vector<std::string>& args);
// `quadra report SUBJECT` (report_command.cpp, quadra-report's main); args
// start with the subject.
int runReport(const std::vector<std::string>& args);
// `quadra report sat-precision` (report_sat_precision.cpp).
int runSatPrecisionReport(const std::vector<std::string>& args);
// `quadra report frames` (report_frames.cpp).
int runFramesReport(const std::vector<std::string>& args);
// `quadra report stability` (report_stability.cpp).
int runStabilityReport(const std::vector<std::string>& args);
// `quadra report samples` (report_samples.cpp).
int runSamplesReport(const std::vector<std::string>& args);
// `quadra report lighting` (report_lighting.cpp).
int runLightingReport(const std::vector<std::string>& args);

}  // namespace quadra
