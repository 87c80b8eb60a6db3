// From scene-referred radiance to display values (LIGHTING.md "Output"):
// exposure (x 2^EV), then a tone map: Khronos PBR Neutral, ACES (Stephen
// Hill's fit, as the Khronos glTF Sample Viewer's toneMapACES_Hill) or none
// (clamp to [0, 1]); then the piecewise sRGB curve to 8 bits (io/srgb8.h).
// EXR output skips all of it (linear radiance x 2^EV).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace quadra {

enum class ToneMap { PbrNeutral, Aces, None };

const char* toneMapName(ToneMap map);  // "pbr-neutral" | "aces" | "none"
std::optional<ToneMap> parseToneMap(const std::string& name);

// Khronos PBR Neutral (the published reference, Khronos 2024): values whose
// largest channel, after the toe's offset, stays below 0.76 keep their hue
// and are only offset; above it the peak is compressed toward 1 and
// desaturated. In [0, 1] for non-negative input.
void pbrNeutral(const float in[3], float out[3]);
// ACES filmic (Hill's fit of the RRT + ODT): sRGB primaries -> ACES AP1
// with the RRT's saturation, the rational fit, back to sRGB, clamped to [0, 1].
void acesHill(const float in[3], float out[3]);

struct ToneMapping {
  ToneMap map = ToneMap::PbrNeutral;
  float exposure = 0.0f;  // EV: radiance x 2^exposure before the curve
  // rgb radiance -> display-linear values in [0, 1].
  void apply(const float in[3], float out[3]) const;
};

// Premultiplied linear RGBA radiance -> straight 8-bit sRGB r, g, b (tone
// mapped) and UNORM8 alpha, `width` pixels: the tone-mapped twin of
// io/srgb8.h's encodeSrgb8Row.
void toneMapSrgb8Row(const ToneMapping& mapping, const float* rgba, int width, std::uint8_t* out);

// A frame's row as an 8-bit output shows it (PNG files, the APIs' Rgba8Srgb
// targets): None is encodeSrgb8Row's clamp, so frames written before tone
// maps existed keep their bytes; the others are toneMapSrgb8Row at exposure
// 0 (the frame already holds radiance x 2^exposure).
void encodeDisplayRow(ToneMap map, const float* rgba, int width, std::uint8_t* out);

}  // namespace quadra
