// The report subjects in the order the overviews list them, each with one
// line on what it measures: `quadra help` (in quadra) and `quadra report
// --help` (in quadra-report) print the same lines, so both programs include
// this one list; neither links the other's code.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace quadra {

inline std::vector<std::pair<std::string, std::string>> reportSubjects() {
  return {
      {"textures", "every texture filter's speed against its error"},
      {"sat-precision", "the summed-area table's precision against float tables"},
      {"stability", "numerical stability on the hard-case scenes (exit 1 on a failed check)"},
      {"frames", "quadra's frames against Mesa llvmpipe's: times and image difference"},
      {"samples", "samples per pixel: their cost against a reference tracer's frame"},
      {"lighting", "lit frames, quadra's and llvmpipe's: time and error against the lit ideal"}};
}

}  // namespace quadra
