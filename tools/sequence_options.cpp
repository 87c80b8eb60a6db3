// Frame ranges, frame-numbered output names and the choice of animation for
// `quadra render --sequence`.
#include "sequence_options.h"

#include <string>

#include "cli_options.h"
#include "core/error.h"

namespace quadra {

namespace {

// Frame numbers stay below 10^7, so a frame's time and name stay exact.
constexpr int kMaxFrame = 9999999;

}  // namespace

FrameRange parseFrameRange(const std::string& option, const std::string& text) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size())
    throw Error(option + ": '" + text + "' must be FIRST:LAST (frame numbers)");
  FrameRange range;
  range.first = parseInteger(option, text.substr(0, colon), 0, kMaxFrame);
  range.last = parseInteger(option, text.substr(colon + 1), 0, kMaxFrame);
  if (range.first > range.last)
    throw Error(option + ": '" + text + "' is reversed (FIRST must not exceed LAST)");
  return range;
}

bool hasFrameField(const std::string& pattern) {
  return pattern.find('#') != std::string::npos;
}

std::string framePath(const std::string& pattern, int frame) {
  const std::string number = std::to_string(frame);
  std::string path;
  for (std::size_t i = 0; i < pattern.size();) {
    if (pattern[i] != '#') {
      path += pattern[i++];
      continue;
    }
    const std::size_t end = pattern.find_first_not_of('#', i);
    const std::size_t width = (end == std::string::npos ? pattern.size() : end) - i;
    if (number.size() < width) path.append(width - number.size(), '0');
    path += number;
    i += width;
  }
  return path;
}

int findAnimation(const Scene& scene, const std::string& option, const std::string& text) {
  const std::size_t count = scene.animations.size();
  for (std::size_t i = 0; i < count; ++i) {
    if (scene.animations[i].name == text) return int(i);
  }
  const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
  if (digits && text.size() < 10 && std::stoul(text) < count) return int(std::stoul(text));
  throw Error(scene.name + ": " + option + " '" + text + "': no such animation (the scene has " +
              std::to_string(count) + ")");
}

}  // namespace quadra
