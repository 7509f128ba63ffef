// Accessor reading with every offset checked against the buffer it points into: tinygltf
// parses accessors but does not validate their ranges, and a wrong byteOffset or count in a
// broken file must become a LoadError, not a read past the end of a buffer.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "scene/gltf_internal.h"

namespace ddish::scene::gltf {

namespace {

int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

int component_size(int component_type) {
  switch (component_type) {
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
      return 0;
  }
}

template <typename T>
T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));  // buffers carry no alignment guarantee
  return v;
}

// One component as a float; normalised integers map to [0,1] or [-1,1] as glTF specifies.
float component_value(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      float v = float(load<std::uint8_t>(p));
      return normalized ? v / 255.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      float v = float(load<std::int8_t>(p));
      return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      float v = float(load<std::uint16_t>(p));
      return normalized ? v / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      float v = float(load<std::int16_t>(p));
      return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    default:
      return float(load<std::uint32_t>(p));
  }
}

// An accessor without a buffer view is all zeros (plus sparse values) and has no buffer to bound
// its count; 2^26 elements is far beyond any sensible use.
constexpr std::size_t kMaxUnbackedElements = std::size_t(1) << 26;

// A checked view of `count` elements of `element_size` bytes, `stride` apart.
struct Span {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
};

Span checked_span(const Context& ctx, int view_index, std::size_t offset, std::size_t count,
                  std::size_t element_size, bool allow_stride, const std::string& what) {
  const auto& m = ctx.model;
  if (view_index < 0 || std::size_t(view_index) >= m.bufferViews.size())
    ctx.fail(what + ": buffer view " + std::to_string(view_index) + " does not exist");
  const auto& view = m.bufferViews[std::size_t(view_index)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= m.buffers.size())
    ctx.fail(what + ": buffer " + std::to_string(view.buffer) + " does not exist");
  const auto& buffer = m.buffers[std::size_t(view.buffer)];
  if (view.byteOffset > buffer.data.size() ||
      view.byteLength > buffer.data.size() - view.byteOffset)
    ctx.fail(what + ": buffer view " + std::to_string(view_index) +
             " reaches past the end of buffer " + std::to_string(view.buffer) + " (" +
             std::to_string(buffer.data.size()) + " bytes)");
  std::size_t stride = element_size;
  if (allow_stride && view.byteStride != 0) {
    if (view.byteStride < element_size)
      ctx.fail(what + ": byteStride " + std::to_string(view.byteStride) +
               " is smaller than an element (" + std::to_string(element_size) + " bytes)");
    stride = view.byteStride;
  }
  if (count > 0) {
    constexpr std::size_t kMax = std::numeric_limits<std::size_t>::max();
    if (count - 1 > (kMax - element_size) / stride)
      ctx.fail(what + ": accessor count " + std::to_string(count) + " is out of range");
    std::size_t span = (count - 1) * stride + element_size;
    if (offset > view.byteLength || span > view.byteLength - offset)
      ctx.fail(what + ": accessor range (offset " + std::to_string(offset) + ", " +
               std::to_string(count) + " elements) is out of range of buffer view " +
               std::to_string(view_index) + " (" + std::to_string(view.byteLength) + " bytes)");
  }
  return Span{buffer.data.data() + view.byteOffset + offset, stride};
}

}  // namespace

FloatData read_floats(const Context& ctx, int index, const std::string& what, bool integers) {
  const auto& m = ctx.model;
  if (index < 0 || std::size_t(index) >= m.accessors.size())
    ctx.fail(what + ": accessor " + std::to_string(index) + " does not exist");
  const auto& acc = m.accessors[std::size_t(index)];
  int comps = component_count(acc.type);
  int csize = component_size(acc.componentType);
  if (comps == 0 || csize == 0)
    ctx.fail(what + ": accessor " + std::to_string(index) + " has an invalid type");
  if (acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !acc.normalized && !integers)
    ctx.fail(what + ": accessor " + std::to_string(index) +
             " holds integers that are not normalised (quantised geometry is not supported)");
  const std::string label = what + " (accessor " + std::to_string(index) + ")";

  // Ranges are checked before anything is allocated: a count of 2^40 must not reach assign().
  std::size_t element = std::size_t(comps) * std::size_t(csize);
  Span s;
  if (acc.bufferView >= 0)
    s = checked_span(ctx, acc.bufferView, acc.byteOffset, acc.count, element, true, label);
  else if (acc.count > kMaxUnbackedElements)
    ctx.fail(label + ": accessor count " + std::to_string(acc.count) + " is out of range");
  FloatData out;
  out.components = comps;
  out.values.assign(acc.count * std::size_t(comps), 0.0f);  // no buffer view = zeros (glTF)
  if (acc.bufferView >= 0) {
    for (std::size_t i = 0; i < acc.count; ++i)
      for (int c = 0; c < comps; ++c)
        out.values[i * std::size_t(comps) + std::size_t(c)] = component_value(
            s.data + i * s.stride + std::size_t(c * csize), acc.componentType, acc.normalized);
  }
  if (acc.sparse.isSparse) {
    const auto& sp = acc.sparse;
    if (sp.count < 0 || std::size_t(sp.count) > acc.count)
      ctx.fail(label + ": sparse count " + std::to_string(sp.count) + " is out of range");
    int isize = component_size(sp.indices.componentType);
    if (isize == 0 || sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
        sp.indices.byteOffset < 0 || sp.values.byteOffset < 0)
      ctx.fail(label + ": invalid sparse indices");
    std::size_t n = std::size_t(sp.count);
    Span si = checked_span(ctx, sp.indices.bufferView, std::size_t(sp.indices.byteOffset), n,
                           std::size_t(isize), false, label + " sparse indices");
    Span sv = checked_span(ctx, sp.values.bufferView, std::size_t(sp.values.byteOffset), n, element,
                           false, label + " sparse values");
    for (std::size_t k = 0; k < n; ++k) {
      std::size_t target =
          std::size_t(component_value(si.data + k * si.stride, sp.indices.componentType, false));
      if (target >= acc.count)
        ctx.fail(label + ": sparse index " + std::to_string(target) + " is out of range");
      for (int c = 0; c < comps; ++c)
        out.values[target * std::size_t(comps) + std::size_t(c)] = component_value(
            sv.data + k * sv.stride + std::size_t(c * csize), acc.componentType, acc.normalized);
    }
  }
  return out;
}

std::vector<std::uint32_t> read_indices(const Context& ctx, int index, const std::string& what) {
  const auto& m = ctx.model;
  if (index < 0 || std::size_t(index) >= m.accessors.size())
    ctx.fail(what + ": accessor " + std::to_string(index) + " does not exist");
  const auto& acc = m.accessors[std::size_t(index)];
  const std::string label = what + " indices (accessor " + std::to_string(index) + ")";
  if (acc.type != TINYGLTF_TYPE_SCALAR ||
      (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
       acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    ctx.fail(label + ": indices must be unsigned byte, short or int scalars");
  if (acc.sparse.isSparse || acc.bufferView < 0)
    ctx.fail(label + ": indices must come from a buffer view");
  int csize = component_size(acc.componentType);
  // Index buffer views never have a stride (glTF), so elements are packed.
  Span s = checked_span(ctx, acc.bufferView, acc.byteOffset, acc.count, std::size_t(csize), false,
                        label);
  std::vector<std::uint32_t> out(acc.count);
  for (std::size_t i = 0; i < acc.count; ++i) {
    const unsigned char* p = s.data + i * s.stride;
    switch (acc.componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        out[i] = load<std::uint8_t>(p);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        out[i] = load<std::uint16_t>(p);
        break;
      default:
        out[i] = load<std::uint32_t>(p);
        break;
    }
  }
  return out;
}

}  // namespace ddish::scene::gltf
