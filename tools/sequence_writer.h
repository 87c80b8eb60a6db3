// Writing a sequence's frames while the next ones render: the render loop
// hands each finished Frame to a writer thread of its own and carries on
// with a spare one, so frame k+1 renders while frame k is compressed and
// written. Frames are written, and reported, in the order they were handed
// over; a write that fails stops the writer and its error reaches the loop.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/parallel.h"
#include "io/frame.h"
#include "io/image_io.h"

namespace quadra {

class SequenceWriter {
 public:
  // Called on the writer thread once a frame's files are all written.
  using Written = std::function<void(const std::vector<std::string>& paths)>;

  // threads: for the writers' own compression (io/image_io.h). queueDepth:
  // how many handed-over frames may wait unwritten before submit blocks, and
  // so how many frame buffers (besides the one rendering) the writer keeps.
  // exr: how the EXR files store their pixels; pngToneMap: how the PNG
  // files map radiance to [0, 1].
  SequenceWriter(int threads, std::size_t queueDepth, const ExrSettings& exr = {},
                 ToneMap pngToneMap = ToneMap::None);
  // Writes what is still queued (each frame handed over is complete), then
  // stops; errors at this point are dropped, finish() is the way to see them.
  ~SequenceWriter();
  SequenceWriter(const SequenceWriter&) = delete;
  SequenceWriter& operator=(const SequenceWriter&) = delete;

  // Queues `frame` to be written to each of `paths`, taking its buffers and
  // leaving a written frame's buffers (or an empty Frame) in their place.
  // Blocks while queueDepth frames wait. Throws the error of an earlier
  // write that failed.
  void submit(Frame& frame, std::vector<std::string> paths, Written written);

  // Waits until every queued frame is written; throws the first write error.
  // Returns the writer thread's total time writing, in ms.
  double finish();

 private:
  struct Job {
    Frame frame;
    std::vector<std::string> paths;
    Written written;
  };
  void run();

  Executor executor_;
  const std::size_t queueDepth_;
  const ExrSettings exr_;
  const ToneMap pngToneMap_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> queue_;
  std::vector<Frame> spares_;  // written frames, whose buffers the loop reuses
  bool busy_ = false;          // the writer holds a job outside the queue
  bool stopping_ = false;
  std::exception_ptr error_;
  double writeMs_ = 0.0;
  std::thread thread_;  // last: started once everything above exists
};

}  // namespace quadra
