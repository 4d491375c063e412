// glTF importer, the scene: each primitive unrolled into triangles (its
// accessors or its Draco data), the node hierarchy checked to be trees and
// walked with world matrices, KHR_lights_punctual lights placed, and the
// output's size checked before it is allocated (gltf.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "gltf.h"

namespace geom::detail::gltf {

void assemble(const std::vector<float>& positions, const std::vector<uint32_t>& idx, int mode, Decoded& d) {
  std::vector<uint32_t> tris;
  const size_t n = idx.size();
  if (mode == kTriangles) {
    tris.assign(idx.begin(), idx.begin() + ptrdiff_t(n - n % 3));
  } else if (n >= 3) {
    tris.reserve(3 * (n - 2));
    for (size_t i = 0; i + 2 < n; ++i) {
      uint32_t a, b, c;
      if (mode == kTriangleStrip) {
        a = idx[i], b = idx[i + 1 + i % 2], c = idx[i + 2 - i % 2];
      } else {
        a = idx[i + 1], b = idx[i + 2], c = idx[0];
      }
      if (a == b || b == c || a == c) continue;
      tris.insert(tris.end(), {a, b, c});
    }
  }
  std::vector<uint32_t> remap(positions.size() / 3, 0xffffffffu);
  d.indices.resize(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) {
    uint32_t& r = remap[tris[i]];
    if (r == 0xffffffffu) {
      r = uint32_t(d.positions.size() / 3);
      d.positions.insert(d.positions.end(), &positions[3 * size_t(tris[i])], &positions[3 * size_t(tris[i])] + 3);
    }
    d.indices[i] = r;
  }
  d.triangles = true;
}

namespace {

void decode_primitive(const Model& model, int mesh_index, int prim_index, const SideTable& side,
                      const std::string& file, uint64_t budget, std::vector<std::string>& warnings, Decoded& d) {
  const Primitive& prim = model.meshes[size_t(mesh_index)].primitives[size_t(prim_index)];
  const std::string what = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(prim_index);
  static const char* const kModeNames[] = {"points", "lines", "line loop", "line strip"};
  if (prim.mode >= 0 && prim.mode <= 3) {
    warnings.push_back(file + ": " + what + ": " + kModeNames[prim.mode] + " (mode " + std::to_string(prim.mode) +
                       ") skipped, only triangles are imported");
    return;
  }
  if (prim.mode > 6 || prim.mode < 0)
    refuse(what + ": mode " + std::to_string(prim.mode) + " is not a glTF primitive mode");
  if (auto it = side.draco.find({mesh_index, prim_index}); it != side.draco.end()) {
    decode_draco(model, prim, it->second, what, d);
    return;
  }
  auto pos = prim.attributes.find("POSITION");
  if (pos == prim.attributes.end()) {
    warnings.push_back(file + ": " + what + " has no POSITION attribute, skipped");
    return;
  }
  if (pos->second < 0 || size_t(pos->second) >= model.accessors.size())
    refuse(what + ": POSITION refers to accessor " + std::to_string(pos->second) + ", but the file has " +
           str(model.accessors.size()));
  const Accessor& pa = model.accessors[size_t(pos->second)];
  if (pa.type != kVec3)
    refuse(what + ": POSITION accessor " + std::to_string(pos->second) + " is " + type_name(pa.type) + ", not VEC3");
  std::vector<float> positions;
  read_accessor(model, pos->second, what + " POSITION", budget, positions);
  const size_t nv = positions.size() / 3;

  std::vector<uint32_t> idx;
  if (auto ind = side.indices.find({mesh_index, prim_index}); ind != side.indices.end()) {
    const int indices = ind->second;
    if (indices < 0 || size_t(indices) >= model.accessors.size())
      refuse(what + ": indices refer to accessor " + std::to_string(indices) + ", but the file has " +
             str(model.accessors.size()));
    const Accessor& ia = model.accessors[size_t(indices)];
    if (ia.type != kScalar ||
        (ia.componentType != kUnsignedByte && ia.componentType != kUnsignedShort && ia.componentType != kUnsignedInt) ||
        ia.normalized)
      refuse(what + ": indices accessor " + std::to_string(indices) +
             " is not a SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    read_accessor(model, indices, what + " indices", budget, idx);
    const uint32_t restart = uint32_t(normalized_max(ia.componentType));
    for (size_t i = 0; i < idx.size(); ++i) {
      if (idx[i] >= nv)
        refuse("accessor " + std::to_string(indices) + " (indices of " + what + "): element " + str(i) + " is vertex " +
               str(idx[i]) + ", out of range (" + str(nv) + " vertices)");
      if (idx[i] == restart)  // glTF 2.0 section 3.7.2.1: MUST NOT be used
        refuse("accessor " + std::to_string(indices) + " (indices of " + what + "): element " + str(i) + " is " +
               str(restart) + ", the primitive restart value, which glTF forbids");
    }
  } else {
    if (nv > 0xffffffffu) refuse(what + ": more than 2^32 - 1 vertices");
    idx.resize(nv);
    for (size_t i = 0; i < nv; ++i) idx[i] = uint32_t(i);
  }
  if (prim.mode == kTriangles && idx.size() % 3 != 0)
    warnings.push_back(file + ": " + what + ": " + str(idx.size()) + " indices is not a multiple of 3, the last " +
                       str(idx.size() % 3) + " ignored");
  assemble(positions, idx, prim.mode, d);
}

// ------------------------------------------------------------ scene graph

using Mat4 = std::array<double, 16>;  // column-major, as glTF stores it
constexpr Mat4 kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[c * 4 + k];
      r[c * 4 + row] = s;
    }
  return r;
}

// The node's local matrix: `matrix`, else T * R * S (glTF 2.0 section 3.5.3).
Mat4 local_matrix(const Node& n, size_t index) {
  const std::string what = "node " + str(index);
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16) refuse(what + ": matrix has " + str(n.matrix.size()) + " numbers, not 16");
    Mat4 m;
    std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
    return m;
  }
  if (!n.translation.empty() && n.translation.size() != 3)
    refuse(what + ": translation has " + str(n.translation.size()) + " numbers, not 3");
  if (!n.scale.empty() && n.scale.size() != 3) refuse(what + ": scale has " + str(n.scale.size()) + " numbers, not 3");
  if (!n.rotation.empty() && n.rotation.size() != 4)
    refuse(what + ": rotation has " + str(n.rotation.size()) + " numbers, not 4");
  double t[3] = {0, 0, 0}, s[3] = {1, 1, 1}, q[4] = {0, 0, 0, 1};
  std::copy(n.translation.begin(), n.translation.end(), t);
  std::copy(n.scale.begin(), n.scale.end(), s);
  std::copy(n.rotation.begin(), n.rotation.end(), q);
  double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(len > 0) || !std::isfinite(len)) refuse(what + ": rotation is not a usable quaternion");
  for (double& c : q) c /= len;
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                       2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                       2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};  // columns
  Mat4 m{};
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row) m[c * 4 + row] = r[c * 3 + row] * s[c];
  m[12] = t[0], m[13] = t[1], m[14] = t[2], m[15] = 1;
  return m;
}

struct Instance {
  int node, mesh;
  Mat4 world;
};

// Picks the scene's root nodes, checks that the node graph is a set of trees,
// and returns every node of the scene with its world matrix (each once).
std::vector<Instance> walk_scene(const Model& model) {
  const size_t n = model.nodes.size();
  std::vector<int> parent(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const Node& node = model.nodes[i];
    if (node.mesh < -1 || node.mesh >= int(model.meshes.size()))
      refuse("node " + str(i) + " refers to mesh " + std::to_string(node.mesh) + ", but the file has " +
             str(model.meshes.size()));
    for (int c : node.children) {
      if (c < 0 || size_t(c) >= n)
        refuse("node " + str(i) + " has child " + std::to_string(c) + ", but the file has " + str(n) + " nodes");
      if (size_t(c) == i) refuse("node " + str(i) + " is its own child (a node loop)");
      if (parent[size_t(c)] != -1)
        refuse("node " + std::to_string(c) + " has two parents (nodes " + std::to_string(parent[size_t(c)]) + " and " +
               str(i) + ")");
      parent[size_t(c)] = int(i);
    }
  }
  // With one parent per node, a node whose parent chain never reaches a root
  // lies on a cycle or below one.
  std::vector<char> state(n, 0);  // 0 unknown, 1 reaches a root, 2 on the current chain
  for (size_t i = 0; i < n; ++i) {
    std::vector<size_t> chain;
    size_t k = i;
    while (state[k] == 0 && parent[k] != -1) {
      state[k] = 2;
      chain.push_back(k);
      k = size_t(parent[k]);
    }
    if (state[k] == 2) refuse("the node hierarchy has a cycle through node " + str(k));
    for (size_t c : chain) state[c] = 1;
    state[k] = 1;
  }

  std::vector<int> roots;
  if (!model.scenes.empty() || model.defaultScene >= 0) {
    int s = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (size_t(s) >= model.scenes.size())
      refuse("the default scene " + std::to_string(s) + " does not exist (the file has " + str(model.scenes.size()) +
             " scenes)");
    std::vector<char> listed(n, 0);
    for (int r : model.scenes[size_t(s)].nodes) {
      if (r < 0 || size_t(r) >= n)
        refuse("scene " + std::to_string(s) + " lists node " + std::to_string(r) + ", but the file has " + str(n) +
               " nodes");
      if (parent[size_t(r)] != -1)
        refuse("scene " + std::to_string(s) + " lists node " + std::to_string(r) + ", a child of node " +
               std::to_string(parent[size_t(r)]) + ", as a root");
      if (listed[size_t(r)]++) refuse("scene " + std::to_string(s) + " lists node " + std::to_string(r) + " twice");
      roots.push_back(r);
    }
  } else {
    for (size_t i = 0; i < n; ++i)
      if (parent[i] == -1) roots.push_back(int(i));
  }

  std::vector<Instance> out;
  std::vector<std::pair<int, Mat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, kIdentity});
  while (!stack.empty()) {
    auto [index, parent_world] = stack.back();
    stack.pop_back();
    const Node& node = model.nodes[size_t(index)];
    Mat4 world = multiply(parent_world, local_matrix(node, size_t(index)));
    out.push_back({index, node.mesh, world});
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world});
  }
  return out;
}

// ------------------------------------------------------------ lights

void add_light(const Model& model, const std::vector<LightDef>& lights, const Instance& inst, const std::string& file,
               Scene& out) {
  const Node& node = model.nodes[size_t(inst.node)];
  if (!node.light.present) return;
  const std::string where = file + ": node " + std::to_string(inst.node);
  if (!node.light.is_int || node.light.index < 0 || size_t(node.light.index) >= lights.size()) {
    out.warnings.push_back(where + " refers to a KHR_lights_punctual light that does not exist, ignored");
    return;
  }
  const int index = node.light.index;
  const LightDef& src = lights[size_t(index)];
  const std::string what = where + ": light " + std::to_string(index);
  Light l;
  if (src.type == "directional")
    l.type = LightType::Directional;
  else if (src.type == "point")
    l.type = LightType::Point;
  else if (src.type == "spot")
    l.type = LightType::Spot;
  else {
    out.warnings.push_back(what + " has no known type (\"" + src.type + "\"), ignored");
    return;
  }
  l.name = src.name;
  const Mat4& m = inst.world;
  double p[3] = {m[12], m[13], m[14]};
  double d[3] = {-m[8], -m[9], -m[10]};  // world image of (0, 0, -1)
  double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
    out.warnings.push_back(what + " has a non-finite position, ignored");
    return;
  }
  if (l.type != LightType::Point && !(len > 0 && std::isfinite(len))) {
    out.warnings.push_back(what + ": the node's transform gives no direction (zero scale), ignored");
    return;
  }
  for (int k = 0; k < 3; ++k) {
    l.position[k] = float(p[k]);
    if (len > 0 && std::isfinite(len)) l.direction[k] = float(d[k] / len);
  }
  if (src.color.size() == 3 && std::all_of(src.color.begin(), src.color.end(), [](double c) { return c >= 0; })) {
    for (int k = 0; k < 3; ++k) l.color[k] = float(src.color[size_t(k)]);
  } else if (!src.color.empty()) {
    out.warnings.push_back(what + ": color is not 3 non-negative numbers, white used");
  }
  if (src.intensity >= 0)
    l.intensity = float(src.intensity);
  else if (!std::isnan(src.intensity))
    out.warnings.push_back(what + ": negative intensity, 1 used");
  if (src.range > 0)
    l.range = float(src.range);
  else if (!std::isnan(src.range))
    out.warnings.push_back(what + ": range is not positive, infinite used");
  if (l.type == LightType::Spot) {
    const double half_pi = 1.5707963267948966;
    double inner = std::isnan(src.inner) ? 0.0 : src.inner;
    double outer = std::isnan(src.outer) ? half_pi / 2 : src.outer;
    if (!(outer > 0 && outer <= half_pi) || !(inner >= 0 && inner < outer)) {
      out.warnings.push_back(what + ": spot cone angles outside 0 <= inner < outer <= pi/2, clamped");
      outer = std::min(std::max(outer, 1e-6), half_pi);
      inner = std::min(std::max(inner, 0.0), outer);
    }
    l.inner_cone = float(inner);
    l.outer_cone = float(outer);
  }
  out.lights.push_back(l);
}

}  // namespace

void build_scene(const Model& model, const SideTable& side, const ImportInput& in, uint64_t max_bytes, Scene& out) {
  validate_ranges(model, side.buffer_has_data);
  std::vector<Instance> nodes = walk_scene(model);

  // Every primitive of every mesh, once (a broken mesh refuses the file even
  // when no node uses it).
  std::vector<std::vector<Decoded>> decoded(model.meshes.size());
  uint64_t skipped = 0;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    decoded[m].resize(model.meshes[m].primitives.size());
    for (size_t p = 0; p < decoded[m].size(); ++p) {
      decode_primitive(model, int(m), int(p), side, in.name, max_bytes, out.warnings, decoded[m][p]);
      if (!decoded[m][p].triangles) ++skipped;
    }
  }

  // The output's size, before it is allocated.
  uint64_t vertices = 0, triangles = 0;
  for (const Instance& inst : nodes) {
    if (inst.mesh < 0) continue;
    for (const Decoded& d : decoded[size_t(inst.mesh)]) {
      vertices += d.positions.size() / 3;
      triangles += d.indices.size() / 3;
    }
  }
  if (in.options.max_triangles && triangles > in.options.max_triangles)
    refuse(str(triangles) + " triangles, over the limit of " + str(in.options.max_triangles));
  if (vertices > 0xffffffffu) refuse("the scene has " + str(vertices) + " vertices, more than 2^32 - 1");
  const uint64_t bytes = vertices * 12 + triangles * (12 + sizeof(TriangleSource));
  if (bytes > max_bytes)
    refuse("the scene expands to " + str(triangles) + " triangles and " + str(vertices) + " vertices (" + str(bytes) +
           " bytes), over the limit of " + str(max_bytes));

  out.positions.reserve(size_t(vertices) * 3);
  out.indices.reserve(size_t(triangles) * 3);
  out.sources.reserve(size_t(triangles));
  uint64_t draco_used = 0, instances = 0;
  for (const Instance& inst : nodes) {
    add_light(model, side.lights, inst, in.name, out);
    if (inst.mesh < 0) continue;
    const Mat4& m = inst.world;
    for (size_t p = 0; p < decoded[size_t(inst.mesh)].size(); ++p) {
      const Decoded& d = decoded[size_t(inst.mesh)][p];
      if (!d.triangles) continue;
      ++instances;
      if (side.draco.count({inst.mesh, int(p)})) ++draco_used;
      const uint32_t base = uint32_t(out.positions.size() / 3);
      for (size_t v = 0; v < d.positions.size(); v += 3) {
        const double x = d.positions[v], y = d.positions[v + 1], z = d.positions[v + 2];
        for (int r = 0; r < 3; ++r) out.positions.push_back(float(m[r] * x + m[4 + r] * y + m[8 + r] * z + m[12 + r]));
      }
      for (uint32_t i : d.indices) out.indices.push_back(base + i);
      TriangleSource src;
      src.file = 0;
      src.mesh = uint32_t(inst.mesh);
      src.primitive = uint32_t(p);
      src.node = uint32_t(inst.node);
      out.sources.insert(out.sources.end(), d.indices.size() / 3, src);
    }
  }
  out.source_counts.push_back({"primitives.instanced", instances});
  out.source_counts.push_back({"primitives.draco", draco_used});
  out.source_counts.push_back({"primitives.skipped", skipped});
}

}  // namespace geom::detail::gltf
