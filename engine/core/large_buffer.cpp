// Mapping large buffers before their first write (core/large_buffer.h).
#include "core/large_buffer.h"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>  // MADV_POPULATE_WRITE where the C library knows it
#include <unistd.h>
#endif

namespace quadra {

void mapForWriting(void* data, std::size_t bytes) {
#if defined(MADV_POPULATE_WRITE)
  if (bytes < (std::size_t(1) << 20)) return;
  const std::uintptr_t page = std::uintptr_t(sysconf(_SC_PAGESIZE));
  const std::uintptr_t begin = (std::uintptr_t(data) + page - 1) & ~(page - 1);
  const std::uintptr_t end = (std::uintptr_t(data) + bytes) & ~(page - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#else
  (void)data;
  (void)bytes;
#endif
}

}  // namespace quadra
