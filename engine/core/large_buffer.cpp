// Mapping large buffers before their first write (core/large_buffer.h).
#include "core/large_buffer.h"

#include <algorithm>
#include <cstdint>

#include "core/parallel.h"

#if defined(__linux__)
#include <sys/mman.h>  // MADV_POPULATE_WRITE where the C library knows it
#include <unistd.h>
#endif

namespace quadra {

void mapForWriting(void* data, std::size_t bytes, const Executor* executor) {
#if defined(MADV_POPULATE_WRITE)
  if (bytes < (std::size_t(1) << 20)) return;
  const std::uintptr_t page = std::uintptr_t(sysconf(_SC_PAGESIZE));
  const std::uintptr_t begin = (std::uintptr_t(data) + page - 1) & ~(page - 1);
  const std::uintptr_t end = (std::uintptr_t(data) + bytes) & ~(page - 1);
  if (end <= begin) return;
  constexpr std::uintptr_t kPiece = std::uintptr_t(4) << 20;  // page multiple
  const std::size_t pieces = std::size_t((end - begin + kPiece - 1) / kPiece);
  const auto populate = [&](std::size_t first, std::size_t last) {
    const std::uintptr_t from = begin + first * kPiece;
    const std::uintptr_t to = std::min(end, begin + last * kPiece);
    madvise(reinterpret_cast<void*>(from), to - from, MADV_POPULATE_WRITE);
  };
  if (executor != nullptr && pieces > 1)
    executor->parallelFor(pieces, 1, populate);
  else
    populate(0, pieces);
#else
  (void)data;
  (void)bytes;
  (void)executor;
#endif
}

}  // namespace quadra
