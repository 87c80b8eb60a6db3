// Large buffers that are filled once, right after they are allocated: decoded
// images, texture levels, the frame. On Linux their first touch costs a page
// fault per 4 KiB (the kernel zeroes each page), about a third of a textured
// model's end-to-end time; asking for transparent huge pages before the first
// write makes that one fault per 2 MiB. Elsewhere, or where the kernel says
// no, it is a plain resize: only the speed differs, never the contents.
#pragma once

#include <cstddef>
#include <vector>

namespace quadra {

// Advises the kernel to back [data, data + bytes) with huge pages where whole
// 2 MiB pages fit; a hint, so failure is ignored.
void adviseHugePages(void* data, std::size_t bytes);

// v.resize(count, value), with the new storage advised before it is touched.
template <class T>
void resizeLarge(std::vector<T>& v, std::size_t count, const T& value = T()) {
  if (count > v.capacity()) {
    std::vector<T> fresh;
    fresh.reserve(count);
    adviseHugePages(fresh.data(), count * sizeof(T));
    fresh.assign(v.begin(), v.end());
    v.swap(fresh);
  }
  v.resize(count, value);
}

}  // namespace quadra
