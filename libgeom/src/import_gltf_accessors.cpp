// glTF importer, the accessors: every bufferView and accessor range checked
// against the bytes its buffer really holds before anything is read, then
// accessors read (any byteStride, normalised integers, sparse substitutions; gltf.h).
#include <algorithm>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "gltf.h"

namespace geom::detail::gltf {

namespace {

int component_size(int type) {
  switch (type) {
    case kByte:
    case kUnsignedByte:
      return 1;
    case kShort:
    case kUnsignedShort:
      return 2;
    case kUnsignedInt:
    case kFloat:
      return 4;
    default:
      return 0;  // INT and DOUBLE are not glTF 2.0 component types
  }
}

int component_count(int type) {
  switch (type) {
    case kScalar:
      return 1;
    case kVec2:
      return 2;
    case kVec3:
      return 3;
    case kVec4:
      return 4;
    case kMat2:
      return 4;
    case kMat3:
      return 9;
    case kMat4:
      return 16;
    default:
      return 0;
  }
}

}  // namespace

const char* type_name(int type) {
  switch (type) {
    case kScalar:
      return "SCALAR";
    case kVec2:
      return "VEC2";
    case kVec3:
      return "VEC3";
    case kVec4:
      return "VEC4";
    case kMat2:
      return "MAT2";
    case kMat3:
      return "MAT3";
    case kMat4:
      return "MAT4";
    default:
      return "unknown";
  }
}

void check_range(const Model& model, const std::string& what, int view_index, uint64_t offset, uint64_t count,
                 uint64_t elem, uint64_t stride) {
  if (view_index < 0 || size_t(view_index) >= model.bufferViews.size())
    refuse(what + " refers to bufferView " + std::to_string(view_index) + ", but the file has " +
           str(model.bufferViews.size()));
  const BufferView& view = model.bufferViews[size_t(view_index)];
  if (count == 0) return;
  uint64_t length = view.byteLength;
  // offset + stride * (count - 1) + elem <= length, without overflow
  bool fits = offset <= length && elem <= length - offset &&
              (count - 1 == 0 || (stride > 0 && (count - 1) <= (length - offset - elem) / stride));
  if (!fits)
    refuse(what + " reads past the end of bufferView " + std::to_string(view_index) + " (" + str(count) +
           " elements of " + str(elem) + " bytes, stride " + str(stride) + ", from byte " + str(offset) + " of " +
           str(length) + "; buffer " + std::to_string(view.buffer) + ")");
}

void validate_ranges(const Model& model, const std::vector<char>& buffer_has_data) {
  for (size_t i = 0; i < model.bufferViews.size(); ++i) {
    const BufferView& v = model.bufferViews[i];
    if (v.buffer < 0 || size_t(v.buffer) >= model.buffers.size())
      refuse("bufferView " + str(i) + " refers to buffer " + std::to_string(v.buffer) + ", but the file has " +
             str(model.buffers.size()));
    if (size_t(v.buffer) >= buffer_has_data.size() || !buffer_has_data[size_t(v.buffer)])
      refuse("bufferView " + str(i) + " refers to buffer " + std::to_string(v.buffer) +
             ", which has no data (no uri, or byteLength 0)");
    uint64_t size = model.buffers[size_t(v.buffer)].data.size();
    if (v.byteOffset > size || v.byteLength > size - v.byteOffset)
      refuse("bufferView " + str(i) + " (bytes " + str(v.byteOffset) + " to " +
             str(uint64_t(v.byteOffset) + v.byteLength) + ") reaches past the end of buffer " +
             std::to_string(v.buffer) + " (" + str(size) + " bytes)");
  }
  for (size_t i = 0; i < model.accessors.size(); ++i) {
    const Accessor& a = model.accessors[i];
    std::string what = "accessor " + str(i);
    int csize = component_size(a.componentType), ncomp = component_count(a.type);
    if (!csize)
      refuse(what + ": componentType " + std::to_string(a.componentType) + " is not a glTF 2.0 component type");
    uint64_t elem = uint64_t(csize) * uint64_t(ncomp);
    if (a.bufferView != -1) {
      if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size())
        refuse(what + " refers to bufferView " + std::to_string(a.bufferView) + ", but the file has " +
               str(model.bufferViews.size()));
      uint64_t stride = model.bufferViews[size_t(a.bufferView)].byteStride;
      if (stride == 0) stride = elem;
      if (stride < elem)
        refuse(what + ": bufferView " + std::to_string(a.bufferView) + " has byteStride " + str(stride) +
               ", smaller than one " + type_name(a.type) + " element (" + str(elem) + " bytes)");
      check_range(model, what, a.bufferView, a.byteOffset, a.count, elem, stride);
    }
    if (!a.sparse.isSparse) continue;
    const auto& s = a.sparse;
    if (s.count < 1 || uint64_t(s.count) > a.count)
      refuse(what + ": sparse count " + std::to_string(s.count) + " is outside 1.." + str(a.count));
    int isize = component_size(s.indices.componentType);
    if (s.indices.componentType == kByte || s.indices.componentType == kShort || s.indices.componentType == kFloat ||
        !isize)
      refuse(what + ": sparse indices componentType " + std::to_string(s.indices.componentType) +
             " is not UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    if (s.indices.byteOffset < 0 || s.values.byteOffset < 0) refuse(what + ": negative sparse byteOffset");
    check_range(model, what + " (sparse indices)", s.indices.bufferView, uint64_t(s.indices.byteOffset),
                uint64_t(s.count), uint64_t(isize), uint64_t(isize));
    check_range(model, what + " (sparse values)", s.values.bufferView, uint64_t(s.values.byteOffset), uint64_t(s.count),
                elem, elem);
  }
}

double normalized_max(int type) {
  switch (type) {
    case kByte:
      return 127.0;
    case kUnsignedByte:
      return 255.0;
    case kShort:
      return 32767.0;
    case kUnsignedShort:
      return 65535.0;
    default:
      return 4294967295.0;
  }
}

namespace {

double read_component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case kByte: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case kUnsignedByte:
      return normalized ? p[0] / 255.0 : p[0];
    case kShort: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case kUnsignedShort: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case kUnsignedInt: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? v / 4294967295.0 : v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

}  // namespace

template <class T>
void read_accessor(const Model& model, int index, const std::string& what, uint64_t budget, std::vector<T>& out) {
  const Accessor& a = model.accessors[size_t(index)];
  const size_t ncomp = size_t(component_count(a.type));
  const size_t csize = size_t(component_size(a.componentType));
  if (a.bufferView == -1 && a.count > budget / (ncomp * sizeof(T)))
    refuse(what + ": accessor " + std::to_string(index) + " has no bufferView and claims " + str(a.count) +
           " elements, over the memory limit");
  out.assign(size_t(a.count) * ncomp, T(0));
  if (a.bufferView != -1) {
    const BufferView& view = model.bufferViews[size_t(a.bufferView)];
    const unsigned char* base = model.buffers[size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
    const size_t stride = view.byteStride ? view.byteStride : ncomp * csize;
    if (a.componentType == kFloat && std::is_same<T, float>::value) {
      for (size_t i = 0; i < a.count; ++i) std::memcpy(&out[i * ncomp], base + i * stride, ncomp * 4);
    } else {
      for (size_t i = 0; i < a.count; ++i)
        for (size_t k = 0; k < ncomp; ++k)
          out[i * ncomp + k] =
              static_cast<T>(read_component(base + i * stride + k * csize, a.componentType, a.normalized));
    }
  }
  if (!a.sparse.isSparse) return;
  const auto& s = a.sparse;
  const BufferView& iv = model.bufferViews[size_t(s.indices.bufferView)];
  const BufferView& vv = model.bufferViews[size_t(s.values.bufferView)];
  const unsigned char* ip = model.buffers[size_t(iv.buffer)].data.data() + iv.byteOffset + size_t(s.indices.byteOffset);
  const unsigned char* vp = model.buffers[size_t(vv.buffer)].data.data() + vv.byteOffset + size_t(s.values.byteOffset);
  const size_t isize = size_t(component_size(s.indices.componentType));
  for (size_t j = 0; j < size_t(s.count); ++j) {
    uint64_t target = uint64_t(read_component(ip + j * isize, s.indices.componentType, false));
    if (target >= a.count)
      refuse(what + ": accessor " + std::to_string(index) + " sparse index " + str(target) + " (entry " + str(j) +
             ") is out of range (" + str(a.count) + " elements)");
    for (size_t k = 0; k < ncomp; ++k)
      out[size_t(target) * ncomp + k] =
          static_cast<T>(read_component(vp + (j * ncomp + k) * csize, a.componentType, a.normalized));
  }
}

template void read_accessor<float>(const Model&, int, const std::string&, uint64_t, std::vector<float>&);
template void read_accessor<uint32_t>(const Model&, int, const std::string&, uint64_t, std::vector<uint32_t>&);

}  // namespace geom::detail::gltf
