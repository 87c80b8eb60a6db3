// SequenceWriter (sequence_writer.h): one thread, a bounded queue, and the
// written frames' buffers handed back to the render loop.
#include "sequence_writer.h"

#include <chrono>
#include <utility>

#include "io/image_io.h"

namespace quadra {

SequenceWriter::SequenceWriter(int threads, std::size_t queueDepth, const ExrSettings& exr,
                               ToneMap pngToneMap)
    : executor_(threads),
      queueDepth_(queueDepth < 1 ? 1 : queueDepth),
      exr_(exr),
      pngToneMap_(pngToneMap),
      thread_([this] { run(); }) {}

SequenceWriter::~SequenceWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void SequenceWriter::submit(Frame& frame, std::vector<std::string> paths, Written written) {
  Frame spare;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return error_ || queue_.size() < queueDepth_; });
    if (error_) std::rethrow_exception(error_);
    queue_.push_back({std::move(frame), std::move(paths), std::move(written)});
    if (!spares_.empty()) {
      spare = std::move(spares_.back());
      spares_.pop_back();
    }
  }
  changed_.notify_all();
  frame = std::move(spare);
}

double SequenceWriter::finish() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return error_ || (queue_.empty() && !busy_); });
  if (error_) std::rethrow_exception(error_);
  return writeMs_;
}

void SequenceWriter::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (queue_.empty() || error_) return;  // stopping, nothing (more) to write
    Job job = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    lock.unlock();
    changed_.notify_all();  // a place in the queue is free
    std::exception_ptr failure;
    const auto start = std::chrono::steady_clock::now();
    try {
      for (const std::string& path : job.paths)
        writeFrame(job.frame, path, &executor_, exr_, pngToneMap_);
      if (job.written) job.written(job.paths);
    } catch (...) {
      failure = std::current_exception();
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    lock.lock();
    writeMs_ += ms;
    busy_ = false;
    if (failure) {
      error_ = failure;
      queue_.clear();  // later frames would go to the same place; the loop stops
    } else if (spares_.size() < queueDepth_) {
      spares_.push_back(std::move(job.frame));
    }
    changed_.notify_all();
  }
}

}  // namespace quadra
