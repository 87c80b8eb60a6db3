// Large buffers that are filled once, right after they are allocated: decoded
// images, texture levels, the frame, the vertex stage's arrays. On Linux
// their first touch costs a page fault per 4 KiB (the kernel maps and zeroes
// each page), a third of a textured model's end-to-end time; asking the
// kernel to map the whole buffer in one call before the first write
// (MADV_POPULATE_WRITE, Linux 5.14) leaves the zeroing and drops the traps.
// Elsewhere, or where the kernel says no, it is a plain resize: only the
// speed differs, never the contents.
//
// Transparent huge pages (MADV_HUGEPAGE) were tried first: one fault per 2
// MiB, and the fastest runs (BoomBoxWithAxes end to end 0.16 s against 0.21
// s populated), but bimodal on this project's VMs, whose balloon reports free
// memory to the host: a huge page comes from a free 2 MiB block the host has
// discarded, and faulting it back in made a third of the runs 0.3-0.5 s.
// Populated 4 KiB pages ran 0.21 s every time (10 alternating runs each).
#pragma once

#include <cstddef>
#include <vector>

namespace quadra {

class Executor;

// Maps the whole pages of [data, data + bytes) for writing, now, in pieces
// on `executor`'s threads when one is given (the kernel zeroes every page,
// so the threads share that work); a hint, so failure is ignored. Below a
// megabyte it does nothing (a syscall costs more than the faults it saves).
void mapForWriting(void* data, std::size_t bytes, const Executor* executor = nullptr);

// v.resize(count, value), with new storage mapped before it is touched.
template <class T>
void resizeLarge(std::vector<T>& v, std::size_t count, const T& value = T(),
                 const Executor* executor = nullptr) {
  if (count > v.capacity()) {
    std::vector<T> fresh;
    fresh.reserve(count);
    mapForWriting(fresh.data(), count * sizeof(T), executor);
    fresh.assign(v.begin(), v.end());
    v.swap(fresh);
  }
  v.resize(count, value);
}

}  // namespace quadra
