// DrawState: the fixed-function state one instance is drawn with (depth test
// and write, the depth compare function, face culling, blending), as an
// embedder states it per draw, in the vocabulary of GL's
// glDepthFunc / glCullFace / glBlendFuncSeparate / glBlendEquationSeparate.
// An instance without one is drawn as its material says (scene.h Instance).
//
// Colours are premultiplied linear floats in the frame, so the blend's
// "source" is the shaded colour premultiplied by its alpha: premultiplied
// "over" is (Add, One, OneMinusSrcAlpha) on every channel.
#pragma once

#include <cstdint>

namespace quadra {

// Passes when `fragment OP stored` holds. Stated for DepthMode::Standard
// (smaller = nearer); a reversed-depth frame (larger = nearer) swaps Less
// with Greater and LessEqual with GreaterEqual (api/camera.h DepthMode), so
// a draw's "nearer wins" stays that whatever the frame's depth mode.
enum class CompareFunction : std::uint8_t {
  Never,
  Less,
  Equal,
  LessEqual,
  Greater,
  NotEqual,
  GreaterEqual,
  Always
};

// Which faces are dropped. Front faces are counter-clockwise with y up
// (glTF's and GL's default), mirrored by a world matrix of negative determinant.
enum class CullMode : std::uint8_t { None, Back, Front };

// result = equation(source * sourceFactor, destination * destinationFactor);
// Min and Max take the unscaled colours (GL ignores the factors there too).
enum class BlendEquation : std::uint8_t { Add, Subtract, ReverseSubtract, Min, Max };

// A factor per channel: the colour ones take each channel's own value (the
// alpha channel's is alpha), the alpha ones take alpha on every channel.
enum class BlendFactor : std::uint8_t {
  Zero,
  One,
  SrcColor,
  OneMinusSrcColor,
  DstColor,
  OneMinusDstColor,
  SrcAlpha,
  OneMinusSrcAlpha,
  DstAlpha,
  OneMinusDstAlpha
};

struct BlendState {
  bool enabled = false;  // off: the fragment replaces what is there
  BlendEquation colorEquation = BlendEquation::Add;
  BlendEquation alphaEquation = BlendEquation::Add;
  BlendFactor srcColor = BlendFactor::One, dstColor = BlendFactor::Zero;
  BlendFactor srcAlpha = BlendFactor::One, dstAlpha = BlendFactor::Zero;

  // glBlendFunc / glBlendEquation: one setting for colour and alpha alike.
  static constexpr BlendState uniform(BlendEquation equation, BlendFactor src, BlendFactor dst) {
    return {true, equation, equation, src, dst, src, dst};
  }
  // Premultiplied "over": dst' = src + (1 - src alpha) dst.
  static constexpr BlendState premultipliedOver() {
    return uniform(BlendEquation::Add, BlendFactor::One, BlendFactor::OneMinusSrcAlpha);
  }
  // dst' = src + dst.
  static constexpr BlendState additive() {
    return uniform(BlendEquation::Add, BlendFactor::One, BlendFactor::One);
  }
  bool operator==(const BlendState&) const = default;
};

struct DrawState {
  // Off: every fragment passes and none writes depth (GL: a disabled depth
  // test does not update the depth buffer), whatever depthWrite says.
  bool depthTest = true;
  bool depthWrite = true;
  CompareFunction depthCompare = CompareFunction::Less;
  CullMode cull = CullMode::Back;
  BlendState blend;
  bool operator==(const DrawState&) const = default;
};

// The compare a frame's kernels run for `compare` stated for standard depth:
// in a reversed-depth frame, Less becomes Greater (and so on).
constexpr CompareFunction compareForDepth(CompareFunction compare, bool reversed) {
  if (!reversed) return compare;
  switch (compare) {
    case CompareFunction::Less:
      return CompareFunction::Greater;
    case CompareFunction::LessEqual:
      return CompareFunction::GreaterEqual;
    case CompareFunction::Greater:
      return CompareFunction::Less;
    case CompareFunction::GreaterEqual:
      return CompareFunction::LessEqual;
    default:
      return compare;
  }
}

}  // namespace quadra
