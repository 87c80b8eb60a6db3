// The spelling of filters and wrap modes on the command line and in reports;
// one table per enum so names and parsing cannot drift apart.
#include "texture/sampler_state.h"

#include <array>
#include <string_view>

namespace quadra {

namespace {

struct FilterSpelling {
  Filter filter;
  const char* name;
};

// The first entry for each filter is its canonical name; later ones are aliases.
constexpr std::array<FilterSpelling, 10> kFilterSpellings = {{
    {Filter::Nearest, "nearest"},
    {Filter::Bilinear, "bilinear"},
    {Filter::NearestMip, "nearest-mip"},
    {Filter::Trilinear, "trilinear"},
    {Filter::Anisotropic, "aniso"},
    {Filter::Anisotropic, "anisotropic"},
    {Filter::Ewa, "ewa"},
    {Filter::Area, "area"},
    {Filter::SummedArea, "sat"},
    {Filter::Ripmap, "ripmap"},
}};

struct WrapSpelling {
  WrapMode wrap;
  const char* name;
};

constexpr std::array<WrapSpelling, 4> kWrapSpellings = {{
    {WrapMode::Repeat, "repeat"},
    {WrapMode::MirroredRepeat, "mirror"},
    {WrapMode::ClampToEdge, "clamp"},
    {WrapMode::ClampToBorder, "border"},
}};

}  // namespace

const char* filterName(Filter f) {
  for (const FilterSpelling& s : kFilterSpellings) {
    if (s.filter == f) return s.name;
  }
  return "unknown";
}

bool parseFilter(const std::string& name, Filter& out) {
  for (const FilterSpelling& s : kFilterSpellings) {
    if (name == std::string_view(s.name)) {
      out = s.filter;
      return true;
    }
  }
  return false;
}

std::string filterNames() {
  std::string names;
  for (const Filter f : kEveryFilter)
    names += (names.empty() ? "" : ", ") + std::string(filterName(f));
  return names;
}

const char* wrapName(WrapMode w) {
  for (const WrapSpelling& s : kWrapSpellings) {
    if (s.wrap == w) return s.name;
  }
  return "unknown";
}

bool parseWrap(const std::string& name, WrapMode& out) {
  for (const WrapSpelling& s : kWrapSpellings) {
    if (name == std::string_view(s.name)) {
      out = s.wrap;
      return true;
    }
  }
  return false;
}

}  // namespace quadra
