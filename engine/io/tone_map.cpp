// The tone maps of tone_map.h, each from its published formula.
#include "io/tone_map.h"

#include <algorithm>
#include <cmath>

#include "io/srgb8.h"

namespace quadra {

const char* toneMapName(ToneMap map) {
  switch (map) {
    case ToneMap::PbrNeutral:
      return "pbr-neutral";
    case ToneMap::Aces:
      return "aces";
    case ToneMap::None:
      return "none";
  }
  return "?";
}

std::optional<ToneMap> parseToneMap(const std::string& name) {
  for (ToneMap map : {ToneMap::PbrNeutral, ToneMap::Aces, ToneMap::None})
    if (name == toneMapName(map)) return map;
  return std::nullopt;
}

void pbrNeutral(const float in[3], float out[3]) {
  constexpr float kStartCompression = 0.8f - 0.04f;
  constexpr float kDesaturation = 0.15f;
  const float x = std::min(in[0], std::min(in[1], in[2]));
  const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
  float c[3] = {in[0] - offset, in[1] - offset, in[2] - offset};
  const float peak = std::max(c[0], std::max(c[1], c[2]));
  if (peak < kStartCompression) {
    std::copy(c, c + 3, out);
    return;
  }
  constexpr float d = 1.0f - kStartCompression;
  const float newPeak = 1.0f - d * d / (peak + d - kStartCompression);
  const float scale = newPeak / peak;
  const float g = 1.0f - 1.0f / (kDesaturation * (peak - newPeak) + 1.0f);
  for (int k = 0; k < 3; ++k) {
    const float scaled = c[k] * scale;
    out[k] = scaled + (newPeak - scaled) * g;
  }
}

void acesHill(const float in[3], float out[3]) {
  // Rows of the input (sRGB -> XYZ -> D65 to D60 -> AP1 -> RRT_SAT) and
  // output (ODT_SAT -> XYZ -> D60 to D65 -> sRGB) matrices of Hill's fit.
  static constexpr float kIn[3][3] = {{0.59719f, 0.35458f, 0.04823f},
                                      {0.07600f, 0.90834f, 0.01566f},
                                      {0.02840f, 0.13383f, 0.83777f}};
  static constexpr float kOut[3][3] = {{1.60475f, -0.53108f, -0.07367f},
                                       {-0.10208f, 1.10813f, -0.00605f},
                                       {-0.00327f, -0.07276f, 1.07602f}};
  float fitted[3];
  for (int r = 0; r < 3; ++r) {
    const float v = kIn[r][0] * in[0] + kIn[r][1] * in[1] + kIn[r][2] * in[2];
    const float a = v * (v + 0.0245786f) - 0.000090537f;
    const float b = v * (0.983729f * v + 0.4329510f) + 0.238081f;
    fitted[r] = a / b;
  }
  for (int r = 0; r < 3; ++r) {
    const float v = kOut[r][0] * fitted[0] + kOut[r][1] * fitted[1] + kOut[r][2] * fitted[2];
    out[r] = std::clamp(v, 0.0f, 1.0f);
  }
}

void ToneMapping::apply(const float in[3], float out[3]) const {
  const float scale = std::exp2(exposure);
  float c[3];
  for (int k = 0; k < 3; ++k) {
    const float v = in[k] * scale;
    c[k] = v > 0.0f ? v : 0.0f;  // negative and NaN radiance -> 0
  }
  switch (map) {
    case ToneMap::PbrNeutral:
      pbrNeutral(c, out);
      break;
    case ToneMap::Aces:
      acesHill(c, out);
      break;
    case ToneMap::None:
      std::copy(c, c + 3, out);
      break;
  }
  for (int k = 0; k < 3; ++k) out[k] = std::min(std::max(out[k], 0.0f), 1.0f);
}

void toneMapSrgb8Row(const ToneMapping& mapping, const float* rgba, int width, std::uint8_t* out) {
  static const Srgb8Encoder srgb8;
  for (int x = 0; x < width; ++x, rgba += 4, out += 4) {
    const float alpha = rgba[3];
    float straight[3], mapped[3];
    for (int c = 0; c < 3; ++c) straight[c] = alpha > 0.0f ? rgba[c] / alpha : rgba[c];
    mapping.apply(straight, mapped);
    for (int c = 0; c < 3; ++c) out[c] = srgb8(mapped[c]);
    const float clamped = alpha > 0.0f ? std::min(alpha, 1.0f) : 0.0f;  // NaN -> 0
    out[3] = roundToUnorm8(clamped);
  }
}

void encodeDisplayRow(ToneMap map, const float* rgba, int width, std::uint8_t* out) {
  if (map == ToneMap::None)
    encodeSrgb8Row(rgba, width, out);
  else
    toneMapSrgb8Row(ToneMapping{map, 0.0f}, rgba, width, out);
}

}  // namespace quadra
