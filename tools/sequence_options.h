// What `quadra render --sequence` reads from its command line: the frame
// range, the output names with a run of '#' for the frame number, and the
// animation chosen by name or index; each bad value an Error naming the
// option, found before anything is rendered or written.
#pragma once

#include <string>

#include "scene/scene.h"

namespace quadra {

// Frames FIRST..LAST inclusive (0 <= FIRST <= LAST).
struct FrameRange {
  int first = 0;
  int last = 0;
};

// "FIRST:LAST"; a reversed range (FIRST > LAST) is an Error.
FrameRange parseFrameRange(const std::string& option, const std::string& text);

// Whether `pattern` has a run of '#' for the frame number.
bool hasFrameField(const std::string& pattern);

// `pattern` with each run of '#' replaced by `frame`, zero-padded to the
// run's length (a number longer than the run is written whole).
std::string framePath(const std::string& pattern, int frame);

// The index of the animation `text` names: an animation of that name, else a
// whole-number index; an Error naming `option` and the scene when there is
// no such animation.
int findAnimation(const Scene& scene, const std::string& option, const std::string& text);

}  // namespace quadra
