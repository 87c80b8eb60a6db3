// The lookups CSV of `quadra sample` (header u,v,dudx,dvdx,dudy,dvdy, one
// lookup a row) → columns of floats, read from a file or any stream (the
// fuzz target feeds it memory).
#pragma once

#include <istream>
#include <string>
#include <vector>

#include "texture/texture_sampler.h"

namespace quadra {

// Structure-of-arrays lookups, one column per header field.
struct Lookups {
  std::vector<float> column[6];
  LookupBatch batch() const {
    return {column[0].data(), column[1].data(), column[2].data(), column[3].data(),
            column[4].data(), column[5].data(), column[0].size()};
  }
};

// Throws Error("<source>: line N: <problem>") for a missing or wrong header,
// a field that is not a number, or a row without exactly 6 fields.
Lookups readLookups(std::istream& in, const std::string& source);
// The same from a file; Error("<path>: cannot open for reading") when it cannot be opened.
Lookups readLookups(const std::string& path);

}  // namespace quadra
