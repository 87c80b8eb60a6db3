// Checked accessor reading: every reference and byte range of an accessor (and
// of its sparse part) is verified with overflow-safe 64-bit arithmetic before a
// byte is read, then elements are converted with glTF's normalization rules.
// tinygltf is trusted only to have parsed the JSON, never for a size or offset.
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include "scene/gltf_internal.h"

namespace quadra::gltf {

namespace {

// An accessor without a bufferView allocates its (zero) elements itself, so its
// count is not bounded by any file data: cap it where a scene stops being
// plausible (2^28 elements is 3 GiB as VEC3 floats).
constexpr std::uint64_t kMaxUnbackedCount = std::uint64_t(1) << 28;

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;  // INT and DOUBLE are not glTF 2.0 accessor types
  }
}

int componentsOfType(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT4:
      return 16;  // inverse bind matrices, float only (their reader checks)
    default:
      return 0;  // MAT2 and MAT3 (whose columns glTF pads for small types): nothing reads them
  }
}

bool isUnsignedIntegerType(int componentType) {
  return componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

// a * b + c, false when it does not fit in 64 bits.
bool mulAdd(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t& out) {
  std::uint64_t product = 0;
  if (__builtin_mul_overflow(a, b, &product)) return false;
  return !__builtin_add_overflow(product, c, &out);
}

std::string accessorName(int index) {
  return "accessor " + std::to_string(index);
}

// Bytes [offset, offset + needed) of bufferView `bufferView`, on behalf of `who`.
const std::uint8_t* checkedSpan(const ModelRef& ref, int bufferView, std::uint64_t offset,
                                std::uint64_t needed, bool overflowed, const std::string& who) {
  const ByteRange range = bufferViewBytes(ref, bufferView);
  std::uint64_t end = 0;
  if (overflowed || __builtin_add_overflow(offset, needed, &end)) {
    throw ref.fail(who + " has a byte size that overflows 64 bits");
  }
  if (end > range.size) {
    throw ref.fail(who + " reads past the end of bufferView " + std::to_string(bufferView) +
                   " (needs " + std::to_string(end) + " bytes, has " + std::to_string(range.size) +
                   ")");
  }
  return range.data + offset;
}

// glTF 2.0 §3.11: normalized integers map to [0, 1] or [-1, 1]; the signed
// ones clamp their extra negative code to -1.
template <typename Component>
float toFloat(Component c, bool normalized) {
  if constexpr (std::is_floating_point_v<Component>) {
    return c;
  } else {
    if (!normalized) return float(c);
    constexpr float scale = float(std::numeric_limits<Component>::max());
    return std::max(float(c) / scale, -1.0f);
  }
}

template <typename Component, typename Out>
void convertElements(const std::uint8_t* src, std::uint64_t stride, std::uint64_t count,
                     int components, bool normalized, Out* out) {
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::uint8_t* element = src + i * stride;
    for (int c = 0; c < components; ++c) {
      Component value;
      std::memcpy(&value, element + std::size_t(c) * sizeof(Component), sizeof(Component));
      if constexpr (std::is_same_v<Out, float>) {
        out[i * components + c] = toFloat(value, normalized);
      } else {
        out[i * components + c] = Out(value);
      }
    }
  }
}

// Converts `count` elements of the given layout into out (count * components).
template <typename Out>
void convert(int componentType, const std::uint8_t* src, std::uint64_t stride, std::uint64_t count,
             int components, bool normalized, Out* out) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return convertElements<std::int8_t>(src, stride, count, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return convertElements<std::uint8_t>(src, stride, count, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return convertElements<std::int16_t>(src, stride, count, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return convertElements<std::uint16_t>(src, stride, count, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return convertElements<std::uint32_t>(src, stride, count, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return convertElements<float>(src, stride, count, components, normalized, out);
  }
  QUADRA_CHECK(false);  // viewAccessor admits no other type
}

// Overwrites the elements a sparse accessor substitutes (glTF 2.0 §3.6.2.3).
template <typename Out>
void applySparse(const ModelRef& ref, const AccessorView& view, std::vector<Out>& out) {
  const tinygltf::Accessor& accessor = ref.model.accessors[std::size_t(view.index)];
  if (!accessor.sparse.isSparse) return;
  const std::string who = accessorName(view.index) + " (sparse)";
  const auto& sparse = accessor.sparse;
  if (sparse.count < 1 || std::uint64_t(sparse.count) > view.count) {
    throw ref.fail(who + " has count " + std::to_string(sparse.count) + ", outside 1.." +
                   std::to_string(view.count));
  }
  const int indexType = sparse.indices.componentType;
  if (!isUnsignedIntegerType(indexType)) {
    throw ref.fail(who + " has indices of componentType " + std::to_string(indexType) +
                   " (needs an unsigned integer type)");
  }
  if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
    throw ref.fail(who + " has a negative byteOffset");
  }
  const auto count = std::uint64_t(sparse.count);
  std::uint64_t indexBytes = 0, valueBytes = 0;
  const bool indexOverflow = !mulAdd(count, std::uint64_t(componentSize(indexType)), 0, indexBytes);
  const std::uint64_t elementSize =
      std::uint64_t(componentSize(view.componentType)) * view.components;
  const bool valueOverflow = !mulAdd(count, elementSize, 0, valueBytes);
  const std::uint8_t* indexData =
      checkedSpan(ref, sparse.indices.bufferView, std::uint64_t(sparse.indices.byteOffset),
                  indexBytes, indexOverflow, who + " indices");
  const std::uint8_t* valueData =
      checkedSpan(ref, sparse.values.bufferView, std::uint64_t(sparse.values.byteOffset),
                  valueBytes, valueOverflow, who + " values");

  std::vector<std::uint32_t> targets(count);
  convert(indexType, indexData, std::uint64_t(componentSize(indexType)), count, 1, false,
          targets.data());
  std::vector<Out> values(count * std::uint64_t(view.components));
  convert(view.componentType, valueData, elementSize, count, view.components, view.normalized,
          values.data());
  for (std::uint64_t k = 0; k < count; ++k) {
    if (targets[k] >= view.count) {
      throw ref.fail(who + " substitutes element " + std::to_string(targets[k]) +
                     ", past its count " + std::to_string(view.count));
    }
    std::copy_n(values.begin() + std::ptrdiff_t(k * view.components), view.components,
                out.begin() + std::ptrdiff_t(std::uint64_t(targets[k]) * view.components));
  }
}

template <typename Out>
std::vector<Out> decode(const ModelRef& ref, const AccessorView& view) {
  std::vector<Out> out(view.count * std::uint64_t(view.components), Out(0));
  if (view.data) {
    convert(view.componentType, view.data, view.stride, view.count, view.components,
            view.normalized, out.data());
  }
  applySparse(ref, view, out);
  return out;
}

}  // namespace

std::uint64_t decodedAccessorBytes(const ModelRef& ref, int index) {
  try {
    const AccessorView view = viewAccessor(ref, index, "accessor");
    return view.count * std::uint64_t(view.components) * 4;
  } catch (const Error&) {
    return 0;  // its reader reports the problem, in the words of its role
  }
}

ByteRange bufferViewBytes(const ModelRef& ref, int index) {
  const auto& views = ref.model.bufferViews;
  if (index < 0 || std::size_t(index) >= views.size()) {
    throw ref.fail("bufferView " + std::to_string(index) + " does not exist (the file has " +
                   std::to_string(views.size()) + ")");
  }
  const tinygltf::BufferView& view = views[std::size_t(index)];
  const auto& buffers = ref.model.buffers;
  if (view.buffer < 0 || std::size_t(view.buffer) >= buffers.size()) {
    throw ref.fail("bufferView " + std::to_string(index) + " refers to buffer " +
                   std::to_string(view.buffer) + ", which does not exist");
  }
  const std::vector<unsigned char>& data = buffers[std::size_t(view.buffer)].data;
  std::uint64_t end = 0;
  if (__builtin_add_overflow(std::uint64_t(view.byteOffset), std::uint64_t(view.byteLength),
                             &end) ||
      end > data.size()) {
    throw ref.fail("bufferView " + std::to_string(index) + " (bytes " +
                   std::to_string(view.byteOffset) + " + " + std::to_string(view.byteLength) +
                   ") lies outside buffer " + std::to_string(view.buffer) + " (" +
                   std::to_string(data.size()) + " bytes)");
  }
  return {data.data() + view.byteOffset, std::uint64_t(view.byteLength)};
}

AccessorView viewAccessor(const ModelRef& ref, int index, const std::string& what) {
  const auto& accessors = ref.model.accessors;
  if (index < 0 || std::size_t(index) >= accessors.size()) {
    throw ref.fail(what + " refers to accessor " + std::to_string(index) +
                   ", which does not exist (the file has " + std::to_string(accessors.size()) +
                   ")");
  }
  const tinygltf::Accessor& accessor = accessors[std::size_t(index)];
  const std::string who = accessorName(index);
  AccessorView view;
  view.index = index;
  view.componentType = accessor.componentType;
  view.components = componentsOfType(accessor.type);
  view.normalized = accessor.normalized;
  view.count = std::uint64_t(accessor.count);
  const int size = componentSize(accessor.componentType);
  if (size == 0) {
    throw ref.fail(who + " has unsupported componentType " +
                   std::to_string(accessor.componentType));
  }
  if (view.components == 0) throw ref.fail(who + " (" + what + ") has a MAT2 or MAT3 type");
  if (view.count == 0) throw ref.fail(who + " has count 0");
  const std::uint64_t elementSize = std::uint64_t(size) * std::uint64_t(view.components);

  if (accessor.bufferView < -1) {
    throw ref.fail(who + " refers to bufferView " + std::to_string(accessor.bufferView));
  }
  if (accessor.bufferView == -1) {
    if (view.count > kMaxUnbackedCount) {
      throw ref.fail(who + " has count " + std::to_string(view.count) + ", too many to allocate");
    }
    return view;  // all zeros (plus sparse substitutions)
  }
  bufferViewBytes(ref, accessor.bufferView);  // checks the index before its stride is read
  const std::uint64_t declaredStride =
      ref.model.bufferViews[std::size_t(accessor.bufferView)].byteStride;
  view.stride = declaredStride == 0 ? elementSize : declaredStride;
  if (view.stride < elementSize) {
    throw ref.fail(who + " has elements of " + std::to_string(elementSize) +
                   " bytes but bufferView " + std::to_string(accessor.bufferView) +
                   " has byteStride " + std::to_string(view.stride));
  }
  // The last element ends at byteOffset + (count - 1) * stride + elementSize.
  std::uint64_t needed = 0;
  const bool overflow = !mulAdd(view.count - 1, view.stride, elementSize, needed);
  view.data = checkedSpan(ref, accessor.bufferView, std::uint64_t(accessor.byteOffset), needed,
                          overflow, who);
  return view;
}

std::vector<float> decodeFloats(const ModelRef& ref, const AccessorView& view) {
  return decode<float>(ref, view);
}

std::vector<std::uint32_t> decodeUnsigned(const ModelRef& ref, const AccessorView& view) {
  if (view.components != 1 || !isUnsignedIntegerType(view.componentType)) {
    throw ref.fail(accessorName(view.index) +
                   " must be SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT for indices");
  }
  return decode<std::uint32_t>(ref, view);
}

}  // namespace quadra::gltf
