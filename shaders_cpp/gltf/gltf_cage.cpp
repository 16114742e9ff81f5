#include "shaders_cpp/gltf/gltf_cage.h"
#include "shaders_cpp/cage/non_manifold.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <unordered_map>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "shaders_cpp/animation/rig_pose.h"
#include "shaders_cpp/cage/one_line.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

// Keeps an image's encoded bytes (tinygltf would decode it with stb_image; Tessera's maps go through
// OpenImageIO, which reads more formats, DDS among them).
bool keep_encoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                  int size, void*) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

std::string named(const std::string& kind, int index, const std::string& name) {
  std::string s = kind + " " + std::to_string(index);
  if (!name.empty()) s += " (" + name + ")";
  return s;
}

// The glTF model of one file and the reading of its elements, every error naming the file and element.
class Reader {
 public:
  Reader(std::string path, const tinygltf::Model& m) : path_(std::move(path)), m_(m) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw CageError(path_ + ": " + where + ": " + what);
  }

  const tinygltf::Accessor& accessor(int a, const std::string& where) const {
    if (a < 0 || a >= int(m_.accessors.size()))
      fail(where, "names accessor " + std::to_string(a) + ", but the file has " + std::to_string(m_.accessors.size()));
    return m_.accessors[std::size_t(a)];
  }

  // Accessor `a`'s elements as `want` components each, as double (normalised integers scaled to
  // [0, 1] or [-1, 1] when the accessor says so). `what` names the use for messages.
  std::vector<double> read(int a, int want, const std::string& where, const std::string& what) const {
    if (a < 0 || a >= int(m_.accessors.size()))
      fail(where,
           what + " names accessor " + std::to_string(a) + ", but the file has " + std::to_string(m_.accessors.size()));
    const tinygltf::Accessor& acc = m_.accessors[std::size_t(a)];
    const std::string here = where + ": accessor " + std::to_string(a) + " (" + what + ")";
    const int comps = tinygltf::GetNumComponentsInType(uint32_t(acc.type));
    const int size = tinygltf::GetComponentSizeInBytes(uint32_t(acc.componentType));
    if (comps != want)
      fail(here, "has " + std::to_string(comps) + " components per element, expected " + std::to_string(want));
    if (size <= 0) fail(here, "has an unknown component type " + std::to_string(acc.componentType));
    if (acc.count > (std::size_t(1) << 28)) fail(here, "has " + std::to_string(acc.count) + " elements, too many");
    std::vector<double> out(acc.count * std::size_t(comps), 0.0);
    if (acc.bufferView >= 0) {
      const auto [data, stride, available] = view(acc.bufferView, acc.byteOffset, here);
      const std::size_t elem = std::size_t(size) * std::size_t(comps);
      const std::size_t s = stride ? stride : elem;
      if (acc.count > 0 && (acc.count - 1) * s + elem > available)
        fail(here, "reads past the end of buffer view " + std::to_string(acc.bufferView));
      for (std::size_t i = 0; i < acc.count; ++i)
        for (int c = 0; c < comps; ++c)
          out[i * std::size_t(comps) + std::size_t(c)] =
              component(data + i * s + std::size_t(c * size), acc.componentType, acc.normalized);
    }
    if (acc.sparse.isSparse) {
      const auto& sp = acc.sparse;
      if (sp.count < 0 || std::size_t(sp.count) > acc.count)
        fail(here, "sparse count " + std::to_string(sp.count) + " is out of range");
      const int isize = tinygltf::GetComponentSizeInBytes(uint32_t(sp.indices.componentType));
      if (isize <= 0) fail(here, "sparse indices have an unknown component type");
      const auto [idata, istride, iavail] = view(sp.indices.bufferView, std::size_t(sp.indices.byteOffset), here);
      const auto [vdata, vstride, vavail] = view(sp.values.bufferView, std::size_t(sp.values.byteOffset), here);
      const std::size_t elem = std::size_t(size) * std::size_t(comps);
      if (std::size_t(sp.count) * std::size_t(isize) > iavail || std::size_t(sp.count) * elem > vavail)
        fail(here, "sparse indices or values read past the end of their buffer view");
      (void)istride, (void)vstride;
      for (std::size_t k = 0; k < std::size_t(sp.count); ++k) {
        const double index = component(idata + k * std::size_t(isize), sp.indices.componentType, false);
        if (index < 0 || index >= double(acc.count))
          fail(here, "sparse index " + std::to_string(index) + " is out of range");
        for (int c = 0; c < comps; ++c)
          out[std::size_t(index) * std::size_t(comps) + std::size_t(c)] =
              component(vdata + k * elem + std::size_t(c * size), acc.componentType, acc.normalized);
      }
    }
    return out;
  }

  // A float accessor's elements, every one finite.
  std::vector<float> read_floats(int a, int want, const std::string& where, const std::string& what) const {
    const std::vector<double> d = read(a, want, where, what);
    std::vector<float> f(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      f[i] = float(d[i]);
      if (!std::isfinite(f[i]))
        fail(where + ": accessor " + std::to_string(a) + " (" + what + ")",
             "element " + std::to_string(i / std::size_t(want)) + " is not finite");
    }
    return f;
  }

  // An accessor's component type and count; an index that names no accessor fails naming `where`.
  int component_type(int a, const std::string& where) const { return accessor(a, where).componentType; }
  std::size_t count(int a, const std::string& where) const { return accessor(a, where).count; }
  const std::string& path() const { return path_; }

 private:
  struct View {
    const unsigned char* data;
    std::size_t stride, available;
  };

  View view(int bv, std::size_t offset, const std::string& here) const {
    if (bv < 0 || bv >= int(m_.bufferViews.size()))
      fail(here,
           "names buffer view " + std::to_string(bv) + ", but the file has " + std::to_string(m_.bufferViews.size()));
    const tinygltf::BufferView& v = m_.bufferViews[std::size_t(bv)];
    if (v.buffer < 0 || v.buffer >= int(m_.buffers.size()))
      fail(here,
           "buffer view " + std::to_string(bv) + " names buffer " + std::to_string(v.buffer) + ", which is missing");
    const std::vector<unsigned char>& b = m_.buffers[std::size_t(v.buffer)].data;
    if (v.byteOffset > b.size() || v.byteLength > b.size() - v.byteOffset)
      fail(here, "buffer view " + std::to_string(bv) + " reaches past the end of buffer " + std::to_string(v.buffer) +
                     " (" + std::to_string(b.size()) + " bytes)");
    if (offset > v.byteLength) fail(here, "its byte offset is past the end of buffer view " + std::to_string(bv));
    return {b.data() + v.byteOffset + offset, v.byteStride, v.byteLength - offset};
  }

  static double component(const unsigned char* p, int type, bool normalized) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        std::memcpy(&f, p, 4);
        return f;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const auto c = static_cast<std::int8_t>(p[0]);
        return normalized ? std::max(c / 127.0, -1.0) : c;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t c;
        std::memcpy(&c, p, 2);
        return normalized ? c / 65535.0 : c;
      }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t c;
        std::memcpy(&c, p, 2);
        return normalized ? std::max(c / 32767.0, -1.0) : c;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t c;
        std::memcpy(&c, p, 4);
        return c;
      }
      default: return 0.0;
    }
  }

  std::string path_;
  const tinygltf::Model& m_;
};

bool has_ext(const tinygltf::ExtensionMap& e, const char* name) { return e.find(name) != e.end(); }

glm::dmat4 dmat4_of(const std::vector<double>& m) {
  glm::dmat4 r(1.0);
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 4; ++k) r[c][k] = m[std::size_t(c * 4 + k)];
  return r;
}

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// The nodes as rig nodes, with parents from the children lists; a node with two parents, a child that
// does not exist or a bad transform is an error.
void read_nodes(const Reader& r, const tinygltf::Model& m, CageRig& rig) {
  rig.nodes.resize(m.nodes.size());
  for (std::size_t n = 0; n < m.nodes.size(); ++n) {
    const tinygltf::Node& g = m.nodes[n];
    const std::string where = named("node", int(n), g.name);
    RigNode& out = rig.nodes[n];
    out.name = g.name;
    if ((!g.translation.empty() && g.translation.size() != 3) || (!g.rotation.empty() && g.rotation.size() != 4) ||
        (!g.scale.empty() && g.scale.size() != 3) || (!g.matrix.empty() && g.matrix.size() != 16))
      r.fail(where, "a translation, rotation, scale or matrix has the wrong number of elements");
    if (!all_finite(g.translation) || !all_finite(g.rotation) || !all_finite(g.scale) || !all_finite(g.matrix) ||
        !all_finite(g.weights))
      r.fail(where, "its transform or weights are not finite");
    if (!g.translation.empty()) out.translation = {g.translation[0], g.translation[1], g.translation[2]};
    if (!g.rotation.empty()) out.rotation = glm::dquat(g.rotation[3], g.rotation[0], g.rotation[1], g.rotation[2]);
    if (!g.scale.empty()) out.scale = {g.scale[0], g.scale[1], g.scale[2]};
    if (!g.matrix.empty()) out.has_matrix = true, out.matrix = dmat4_of(g.matrix);
    out.weights = g.weights;
    if (out.weights.empty() && g.mesh >= 0 && g.mesh < int(m.meshes.size()))
      out.weights = m.meshes[std::size_t(g.mesh)].weights;
  }
  for (std::size_t n = 0; n < m.nodes.size(); ++n)
    for (const int c : m.nodes[n].children) {
      if (c < 0 || c >= int(m.nodes.size()))
        r.fail(named("node", int(n), m.nodes[n].name), "child " + std::to_string(c) + " does not exist");
      if (rig.nodes[std::size_t(c)].parent >= 0 || std::size_t(c) == n)
        r.fail(named("node", c, m.nodes[std::size_t(c)].name),
               "has two parents or is its own ancestor (glTF nodes form trees)");
      rig.nodes[std::size_t(c)].parent = int(n);
    }
}

struct WeldKey {
  std::array<std::uint32_t, 3> bits;
  bool operator==(const WeldKey&) const = default;
};
struct WeldHash {
  std::size_t operator()(const WeldKey& k) const {
    return std::hash<std::uint64_t>()((std::uint64_t(k.bits[0]) * 0x9E3779B97F4A7C15ull) ^
                                      (std::uint64_t(k.bits[1]) << 21) ^ (std::uint64_t(k.bits[2]) << 42) ^ k.bits[2]);
  }
};

// Everything an instance's primitives add to the cage and the rig.
class InstanceBuilder {
 public:
  InstanceBuilder(const Reader& r, const tinygltf::Model& m, Cage& cage, CageRig& rig, int instance)
      : r_(r), m_(m), cage_(cage), rig_(rig), instance_(instance) {}

  void add_primitive(int mesh, int p, bool want_uvs);
  int gltf_vertices = 0;

 private:
  // A primitive's vertices welded on exact bits: the cage vertex of each, and whether it was the first
  // occurrence (whose skin weights and morph deltas the cage vertex takes).
  struct Welded {
    std::size_t n = 0;
    std::vector<int> cage_vertex;
    std::vector<bool> first;
  };
  // add_primitive's stages, in order; each fails through the reader, naming `where`.
  Welded weld(const std::vector<float>& positions);
  bool add_uvs(const tinygltf::Primitive& prim, const std::string& where, bool want_uvs, std::size_t n);
  void add_skin(const tinygltf::Primitive& prim, const std::string& where, const Welded& v);
  void add_targets(const tinygltf::Primitive& prim, const std::string& where, const Welded& v);
  // uv_base: the primitive's first entry in cage.uvs, -1 without texture coordinates.
  void add_faces(const tinygltf::Primitive& prim, const std::string& where, const Welded& v, int uv_base);

  const Reader& r_;
  const tinygltf::Model& m_;
  Cage& cage_;
  CageRig& rig_;
  int instance_;
  std::unordered_map<WeldKey, int, WeldHash> weld_;
};

int attribute(const tinygltf::Primitive& prim, const char* name) {
  const auto it = prim.attributes.find(name);
  return it == prim.attributes.end() ? -1 : it->second;
}

void InstanceBuilder::add_primitive(int mesh, int p, bool want_uvs) {
  const tinygltf::Mesh& gm = m_.meshes[std::size_t(mesh)];
  const tinygltf::Primitive& prim = gm.primitives[std::size_t(p)];
  const std::string where = named("mesh", mesh, gm.name) + " primitive " + std::to_string(p);
  const int pos_acc = attribute(prim, "POSITION");
  if (pos_acc < 0) r_.fail(where, "has no POSITION");
  if (r_.component_type(pos_acc, where) != TINYGLTF_COMPONENT_TYPE_FLOAT)
    r_.fail(where, "POSITION is not float (quantized positions are not read)");
  const std::vector<float> pos = r_.read_floats(pos_acc, 3, where, "POSITION");
  gltf_vertices += int(pos.size() / 3);
  const Welded v = weld(pos);
  const int uv_base = int(cage_.uvs.size());
  const bool uvs = add_uvs(prim, where, want_uvs, v.n);
  add_skin(prim, where, v);
  add_targets(prim, where, v);
  add_faces(prim, where, v, uvs ? uv_base : -1);
}

InstanceBuilder::Welded InstanceBuilder::weld(const std::vector<float>& pos) {
  const std::size_t n = pos.size() / 3;
  Welded w{n, std::vector<int>(n), std::vector<bool>(n, false)};
  std::vector<int>& cage_vertex = w.cage_vertex;
  std::vector<bool>& first = w.first;
  for (std::size_t i = 0; i < n; ++i) {
    WeldKey k{{std::bit_cast<std::uint32_t>(pos[3 * i]), std::bit_cast<std::uint32_t>(pos[3 * i + 1]),
               std::bit_cast<std::uint32_t>(pos[3 * i + 2])}};
    // +0 and -0 are one point.
    for (auto& b : k.bits)
      if (b == 0x80000000u) b = 0;
    const auto [it, inserted] = weld_.emplace(k, int(rig_.bind_positions.size()));
    if (inserted) {
      rig_.bind_positions.push_back({pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]});
      rig_.vertex_instance.push_back(instance_);
      first[i] = true;
    }
    cage_vertex[i] = it->second;
  }
  return w;
}

bool InstanceBuilder::add_uvs(const tinygltf::Primitive& prim, const std::string& where, bool want_uvs,
                              std::size_t n) {
  // Texture coordinates: one per glTF vertex, indexed per corner.
  const int uv_acc = attribute(prim, "TEXCOORD_0");
  if ((uv_acc >= 0) != want_uvs)
    r_.fail(where, want_uvs ? "has no TEXCOORD_0 while the cage's other primitives have it"
                            : "has TEXCOORD_0 while the cage's first primitive has none");
  if (uv_acc >= 0) {
    if (r_.count(uv_acc, where) != n) r_.fail(where, "TEXCOORD_0 and POSITION have different counts");
    const std::vector<float> uv = r_.read_floats(uv_acc, 2, where, "TEXCOORD_0");
    for (std::size_t i = 0; i < n; ++i) cage_.uvs.push_back({uv[2 * i], uv[2 * i + 1]});
  }
  return uv_acc >= 0;
}

void InstanceBuilder::add_skin(const tinygltf::Primitive& prim, const std::string& where, const Welded& welded) {
  const std::size_t n = welded.n;
  const std::vector<int>& cage_vertex = welded.cage_vertex;
  const std::vector<bool>& first = welded.first;
  // Skin influences.
  const RigInstance& inst = rig_.instances[std::size_t(instance_)];
  if (inst.skin >= 0) {
    const int joint_count = int(rig_.skins[std::size_t(inst.skin)].joints.size());
    if (rig_.joints.size() < rig_.bind_positions.size()) {
      rig_.joints.resize(rig_.bind_positions.size(), {});
      rig_.weights.resize(rig_.bind_positions.size(), {});
    }
    std::vector<double> joints(n * 8, 0.0), weights(n * 8, 0.0);
    bool any = false;
    for (int set = 0; set < 2; ++set) {
      const int ja = attribute(prim, set == 0 ? "JOINTS_0" : "JOINTS_1");
      const int wa = attribute(prim, set == 0 ? "WEIGHTS_0" : "WEIGHTS_1");
      if ((ja < 0) != (wa < 0))
        r_.fail(where,
                "has JOINTS_" + std::to_string(set) + " without WEIGHTS_" + std::to_string(set) + " or the reverse");
      if (ja < 0) continue;
      any = true;
      if (r_.count(ja, where) != n || r_.count(wa, where) != n)
        r_.fail(where, "JOINTS/WEIGHTS and POSITION have different counts");
      const std::vector<double> j = r_.read(ja, 4, where, "JOINTS_" + std::to_string(set));
      const std::vector<double> w = r_.read(wa, 4, where, "WEIGHTS_" + std::to_string(set));
      for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 4; ++c) {
          joints[i * 8 + std::size_t(set * 4 + c)] = j[i * 4 + std::size_t(c)];
          weights[i * 8 + std::size_t(set * 4 + c)] = w[i * 4 + std::size_t(c)];
        }
    }
    if (!any) r_.fail(where, "draws with a skin but has no JOINTS_0 / WEIGHTS_0");
    std::size_t renormalised = 0;
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0.0;
      for (int c = 0; c < 8; ++c) {
        const double w = weights[i * 8 + std::size_t(c)], j = joints[i * 8 + std::size_t(c)];
        if (!std::isfinite(w) || w < 0.0)
          r_.fail(where, "vertex " + std::to_string(i) + " has a negative or non-finite weight");
        if (w > 0.0 && (j < 0 || j >= joint_count))
          r_.fail(where, "vertex " + std::to_string(i) + " names joint " + std::to_string(long(j)) + ", but skin " +
                             std::to_string(inst.skin) + " has " + std::to_string(joint_count) + " joints");
        sum += w;
      }
      if (!(sum > 0.0)) r_.fail(where, "vertex " + std::to_string(i) + " has no skin weight (all zero)");
      if (std::abs(sum - 1.0) > 2e-3) ++renormalised;
      if (!first[i]) continue;  // a welded copy: the first occurrence's influences stand
      const std::size_t v = std::size_t(cage_vertex[i]);
      float fsum = 0.0f;
      for (int c = 0; c < 8; ++c) fsum += float(weights[i * 8 + std::size_t(c)]);
      for (int c = 0; c < 8; ++c) {
        float w = float(weights[i * 8 + std::size_t(c)]);
        // Weights that already sum to one (as float) keep their bits; others are divided by the sum.
        if (fsum != 1.0f) w = float(weights[i * 8 + std::size_t(c)] / sum);
        rig_.weights[v][std::size_t(c)] = w;
        rig_.joints[v][std::size_t(c)] = w > 0.0f ? std::uint16_t(joints[i * 8 + std::size_t(c)]) : 0;
      }
    }
    if (renormalised)
      cage_.warnings.push_back(r_.path() + ": " + where + ": " + std::to_string(renormalised) +
                               " vertices have skin weights that do not sum to 1; normalised");
  } else if (!rig_.joints.empty()) {
    rig_.joints.resize(rig_.bind_positions.size(), {});
    rig_.weights.resize(rig_.bind_positions.size(), {});
  }
}

void InstanceBuilder::add_targets(const tinygltf::Primitive& prim, const std::string& where, const Welded& v) {
  const RigInstance& inst = rig_.instances[std::size_t(instance_)];
  // Morph targets' position deltas.
  if (int(prim.targets.size()) != inst.target_count)
    r_.fail(where, "has " + std::to_string(prim.targets.size()) + " morph targets, the mesh's first primitive " +
                       std::to_string(inst.target_count) + " (glTF requires the same)");
  for (int t = 0; t < inst.target_count; ++t) {
    std::vector<glm::vec3>& deltas = rig_.target_deltas[std::size_t(inst.first_target + t)];
    deltas.resize(rig_.bind_positions.size(), glm::vec3(0.0f));
    const auto it = prim.targets[std::size_t(t)].find("POSITION");
    if (it == prim.targets[std::size_t(t)].end()) continue;
    if (r_.count(it->second, where) != v.n)
      r_.fail(where, "morph target " + std::to_string(t) + " and POSITION have different counts");
    const std::vector<float> d = r_.read_floats(it->second, 3, where, "target " + std::to_string(t) + " POSITION");
    for (std::size_t i = 0; i < v.n; ++i)
      if (v.first[i]) deltas[std::size_t(v.cage_vertex[i])] = {d[3 * i], d[3 * i + 1], d[3 * i + 2]};
  }
}

void InstanceBuilder::add_faces(const tinygltf::Primitive& prim, const std::string& where, const Welded& v,
                                int uv_base) {
  const std::size_t n = v.n;
  // Triangles, then polygons.
  if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) return;  // the caller warned
  std::vector<std::uint32_t> index;
  if (prim.indices >= 0) {
    const int type = r_.component_type(prim.indices, where);
    if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      r_.fail(where, "indices are not unsigned integers");
    for (const double d : r_.read(prim.indices, 1, where, "indices")) index.push_back(std::uint32_t(d));
  } else {
    for (std::size_t i = 0; i < n; ++i) index.push_back(std::uint32_t(i));
  }
  if (index.size() % 3 != 0) r_.fail(where, "has " + std::to_string(index.size()) + " indices, not a multiple of 3");
  for (std::size_t k = 0; k < index.size(); ++k)
    if (index[k] >= n)
      r_.fail(where, "index " + std::to_string(k) + " is " + std::to_string(index[k]) + ", but POSITION has " +
                         std::to_string(n) + " elements");
  const bool ngon = has_ext(prim.extensions, "FB_ngon_encoding");
  std::vector<std::vector<std::uint32_t>> polys;
  for (std::size_t t = 0; t + 2 < index.size(); t += 3) {
    const std::uint32_t a = index[t], b = index[t + 1], c = index[t + 2];
    if (ngon && !polys.empty() && polys.back()[0] == a)
      polys.back().push_back(c);
    else
      polys.push_back({a, b, c});
  }
  // The encoder of tests/data's cages rotates a few polygons' fan start so that consecutive polygons
  // never share their first vertex; primitive.extras.rotatedFaces = [[face, k], ...] says the decoded
  // polygon starts at the original's corner k. Undoing it gives back the source's start corners (PN
  // patches and the domain's orientation depend on them).
  if (ngon && prim.extras.IsObject() && prim.extras.Has("rotatedFaces") && prim.extras.Get("rotatedFaces").IsArray()) {
    const tinygltf::Value& list = prim.extras.Get("rotatedFaces");
    for (std::size_t e = 0; e < list.ArrayLen(); ++e) {
      const tinygltf::Value& pair = list.Get(int(e));
      if (!pair.IsArray() || pair.ArrayLen() != 2 || !pair.Get(0).IsInt() || !pair.Get(1).IsInt()) continue;
      const int f = pair.Get(0).GetNumberAsInt(), k = pair.Get(1).GetNumberAsInt();
      if (f < 0 || f >= int(polys.size()) || k < 0 || k >= int(polys[std::size_t(f)].size()))
        r_.fail(where, "extras.rotatedFaces names polygon " + std::to_string(f) + " corner " + std::to_string(k) +
                           ", which does not exist");
      auto& poly = polys[std::size_t(f)];
      std::rotate(poly.begin(), poly.end() - k, poly.end());
    }
  }
  for (const auto& poly : polys) {
    cage_.face_offsets.push_back(int(cage_.face_vertices.size()));
    cage_.face_sizes.push_back(int(poly.size()));
    for (const std::uint32_t i : poly) {
      cage_.face_vertices.push_back(v.cage_vertex[i]);
      if (uv_base >= 0) cage_.face_uvs.push_back(uv_base + int(i));
    }
  }
}

// A relative URI's path: %XX escapes decoded (glTF §2.8 uses RFC 3986 URIs).
std::string percent_decoded(const std::string& uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

std::optional<GltfImage> image_of(const Reader& r, const tinygltf::Model& m, int texture, const std::string& where) {
  if (texture < 0) return std::nullopt;
  if (texture >= int(m.textures.size()))
    r.fail(where, "names texture " + std::to_string(texture) + ", which is missing");
  const int source = m.textures[std::size_t(texture)].source;
  if (source < 0 || source >= int(m.images.size()))
    r.fail(where,
           "texture " + std::to_string(texture) + " names image " + std::to_string(source) + ", which is missing");
  const tinygltf::Image& img = m.images[std::size_t(source)];
  GltfImage out;
  out.mime_type = img.mimeType;
  const std::string uri = img.uri;
  if (!uri.empty() && uri.rfind("data:", 0) != 0) {
    const std::string decoded = percent_decoded(uri);
    out.path = (fs::path(r.path()).parent_path() / decoded).string();
    std::error_code ec;
    if (!fs::is_regular_file(out.path, ec))
      r.fail(where, named("image", source, img.name) + " '" + uri + "' not found");
    return out;
  }
  out.path = r.path() + " " + named("image", source, img.name);
  out.bytes.assign(img.image.begin(), img.image.end());
  if (out.bytes.empty() && img.bufferView >= 0 && img.bufferView < int(m.bufferViews.size())) {
    const tinygltf::BufferView& v = m.bufferViews[std::size_t(img.bufferView)];
    if (v.buffer >= 0 && v.buffer < int(m.buffers.size()) &&
        v.byteOffset + v.byteLength <= m.buffers[std::size_t(v.buffer)].data.size())
      out.bytes.assign(m.buffers[std::size_t(v.buffer)].data.begin() + std::ptrdiff_t(v.byteOffset),
                       m.buffers[std::size_t(v.buffer)].data.begin() + std::ptrdiff_t(v.byteOffset + v.byteLength));
  }
  if (out.bytes.empty()) r.fail(where, named("image", source, img.name) + " has no data");
  return out;
}

GltfMaterialMaps material_maps(const Reader& r, const tinygltf::Model& m, int material) {
  GltfMaterialMaps maps;
  if (material < 0) return maps;
  if (material >= int(m.materials.size())) r.fail("material " + std::to_string(material), "is missing");
  const tinygltf::Material& mat = m.materials[std::size_t(material)];
  const std::string where = named("material", material, mat.name);
  maps.normal = image_of(r, m, mat.normalTexture.index, where + " normalTexture");
  const auto it = mat.extensions.find("KHR_materials_displacement");
  if (it != mat.extensions.end() && it->second.IsObject()) {
    const tinygltf::Value& d = it->second;
    const tinygltf::Value& tex = d.Get("displacementGeometryTexture");
    if (tex.IsObject() && tex.Has("index") && tex.Get("index").IsInt())
      maps.displacement = image_of(r, m, tex.Get("index").GetNumberAsInt(), where + " displacementGeometryTexture");
    if (d.Has("displacementGeometryFactor"))
      maps.displacement_factor = float(d.Get("displacementGeometryFactor").GetNumberAsDouble());
    if (d.Has("displacementGeometryOffset"))
      maps.displacement_offset = float(d.Get("displacementGeometryOffset").GetNumberAsDouble());
    if (!std::isfinite(maps.displacement_factor) || !std::isfinite(maps.displacement_offset))
      r.fail(where, "displacementGeometryFactor or Offset is not finite");
  }
  return maps;
}

void read_skins(const Reader& r, const tinygltf::Model& m, CageRig& rig) {
  for (std::size_t s = 0; s < m.skins.size(); ++s) {
    const tinygltf::Skin& g = m.skins[s];
    const std::string where = named("skin", int(s), g.name);
    RigSkin skin;
    skin.name = g.name;
    if (g.joints.empty()) r.fail(where, "has no joints");
    if (g.joints.size() > 65535)
      r.fail(where, "has " + std::to_string(g.joints.size()) + " joints; at most 65535 are read");
    for (const int j : g.joints) {
      if (j < 0 || j >= int(m.nodes.size())) r.fail(where, "joint node " + std::to_string(j) + " does not exist");
      skin.joints.push_back(j);
    }
    if (g.inverseBindMatrices >= 0) {
      const std::vector<float> ibm = r.read_floats(g.inverseBindMatrices, 16, where, "inverseBindMatrices");
      if (ibm.size() / 16 < g.joints.size())
        r.fail(where, "has " + std::to_string(g.joints.size()) + " joints but " + std::to_string(ibm.size() / 16) +
                          " inverse bind matrices");
      for (std::size_t j = 0; j < g.joints.size(); ++j) {
        glm::mat4 mat(1.0f);
        for (int c = 0; c < 4; ++c)
          for (int k = 0; k < 4; ++k) mat[c][k] = ibm[j * 16 + std::size_t(c * 4 + k)];
        skin.inverse_bind.push_back(mat);
      }
    } else {
      skin.inverse_bind.assign(g.joints.size(), glm::mat4(1.0f));
    }
    rig.skins.push_back(std::move(skin));
  }
}

void read_animations(const Reader& r, const tinygltf::Model& m, CageRig& rig, std::vector<std::string>& warnings) {
  for (std::size_t a = 0; a < m.animations.size(); ++a) {
    const tinygltf::Animation& g = m.animations[a];
    Animation anim;
    anim.name = g.name;
    anim.start = INFINITY, anim.end = -INFINITY;
    for (std::size_t c = 0; c < g.channels.size(); ++c) {
      const tinygltf::AnimationChannel& gc = g.channels[c];
      const std::string where = named("animation", int(a), g.name) + " channel " + std::to_string(c);
      if (gc.target_node < 0) continue;  // targets something else (an extension)
      if (gc.target_node >= int(m.nodes.size()))
        r.fail(where, "targets node " + std::to_string(gc.target_node) + ", which is missing");
      if (gc.sampler < 0 || gc.sampler >= int(g.samplers.size()))
        r.fail(where, "names sampler " + std::to_string(gc.sampler) + ", which is missing");
      const tinygltf::AnimationSampler& s = g.samplers[std::size_t(gc.sampler)];
      AnimationChannel ch;
      ch.node = gc.target_node;
      if (gc.target_path == "translation")
        ch.path = AnimationPath::translation, ch.width = 3;
      else if (gc.target_path == "rotation")
        ch.path = AnimationPath::rotation, ch.width = 4;
      else if (gc.target_path == "scale")
        ch.path = AnimationPath::scale, ch.width = 3;
      else if (gc.target_path == "weights") {
        ch.path = AnimationPath::weights;
        const tinygltf::Node& node = m.nodes[std::size_t(gc.target_node)];
        if (node.mesh < 0 || node.mesh >= int(m.meshes.size()) || m.meshes[std::size_t(node.mesh)].primitives.empty()) {
          warnings.push_back(r.path() + ": " + where + ": animates the weights of a node without a mesh; ignored");
          continue;
        }
        ch.width = int(m.meshes[std::size_t(node.mesh)].primitives[0].targets.size());
        if (ch.width == 0) {
          warnings.push_back(r.path() + ": " + where + ": animates weights of a mesh without morph targets; ignored");
          continue;
        }
      } else {
        warnings.push_back(r.path() + ": " + where + ": path '" + gc.target_path + "' is not read; ignored");
        continue;
      }
      if (rig.nodes[std::size_t(ch.node)].has_matrix && ch.path != AnimationPath::weights)
        r.fail(where, "animates node " + std::to_string(ch.node) + ", which has a matrix (glTF forbids it)");
      if (s.interpolation.empty() || s.interpolation == "LINEAR")
        ch.interpolation = Interpolation::linear;
      else if (s.interpolation == "STEP")
        ch.interpolation = Interpolation::step;
      else if (s.interpolation == "CUBICSPLINE")
        ch.interpolation = Interpolation::cubic_spline;
      else
        r.fail(where, "interpolation '" + s.interpolation + "' is not LINEAR, STEP or CUBICSPLINE");
      ch.times = r.read_floats(s.input, 1, where, "sampler input");
      if (ch.times.empty()) r.fail(where, "its sampler has no keys");
      for (std::size_t k = 1; k < ch.times.size(); ++k)
        if (!(ch.times[k] > ch.times[k - 1]))
          r.fail(where, "key times are not strictly increasing at key " + std::to_string(k));
      const int out_comps = ch.path == AnimationPath::weights ? 1 : ch.width;
      ch.values = r.read_floats(s.output, out_comps, where, "sampler output");
      const std::size_t per_key = std::size_t(ch.width) * (ch.interpolation == Interpolation::cubic_spline ? 3 : 1);
      if (ch.values.size() != ch.times.size() * per_key)
        r.fail(where, "has " + std::to_string(ch.times.size()) + " keys but " + std::to_string(ch.values.size()) +
                          " output values (expected " + std::to_string(ch.times.size() * per_key) + ")");
      anim.start = std::min(anim.start, ch.times.front());
      anim.end = std::max(anim.end, ch.times.back());
      anim.channels.push_back(std::move(ch));
    }
    if (anim.channels.empty()) anim.start = anim.end = 0.0f;
    rig.animations.push_back(std::move(anim));
  }
}

}  // namespace

bool is_gltf_path(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".gltf" || ext == ".glb";
}

GltfCage load_gltf_cage(const std::string& path, const GltfSelection& selection) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw CageError(path + ": a directory, not a glTF file");
  if (!fs::is_regular_file(path, ec)) throw CageError(path + ": no such file");
  const auto size = fs::file_size(path, ec);
  if (ec) throw CageError(path + ": cannot read");
  if (size > kMaxGltfFileBytes)
    throw CageError(path + ": " + std::to_string(size) + " bytes, more than a glTF reader takes (2 GiB)");
  std::vector<std::uint8_t> bytes(size);
  std::ifstream f(path, std::ios::binary);
  f.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size));
  if (!f) throw CageError(path + ": cannot read");
  return parse_gltf_cage(bytes, path, selection);
}

// tinygltf's and the JSON parser's error text, short enough for one line: a data URI's payload (often
// megabytes of base64) becomes its length, the parser's "last read" echo of the input is dropped, and
// what is left is capped.
// A .gltf whose JSON parses but a buffer's or image's base64 data URI does not decode: CageError naming
// that element and what is wrong with its payload (its length, not its text). Returns when none is.
static void damaged_data_uris(std::span<const std::uint8_t> bytes, const std::string& path) {
  const nlohmann::json root =
      nlohmann::json::parse(bytes.begin(), bytes.end(), nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded() || !root.is_object()) return;
  for (const char* list : {"buffers", "images"}) {
    if (!root.contains(list) || !root[list].is_array()) continue;
    for (std::size_t i = 0; i < root[list].size(); ++i) {
      const nlohmann::json& item = root[list][i];
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string& uri = item["uri"].get_ref<const std::string&>();
      const std::size_t comma = uri.find(',');
      if (uri.rfind("data:", 0) != 0 || comma == std::string::npos || uri.find(";base64", 0) > comma) continue;
      const std::size_t n = uri.size() - comma - 1;
      const bool alphabet = std::all_of(uri.begin() + std::ptrdiff_t(comma) + 1, uri.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/' || c == '=';
      });
      if (alphabet && n % 4 == 0) continue;
      throw CageError(path + ": " + list + "[" + std::to_string(i) + "]: its base64 data URI " +
                      (alphabet ? "is cut short (" + std::to_string(n) + " characters, not a multiple of 4)"
                                : "holds characters outside base64") +
                      ": the file is damaged or truncated");
    }
  }
}

static std::string loader_message(const std::string& raw) {
  std::string s;
  for (std::size_t i = 0; i < raw.size();) {
    if (raw.compare(i, 5, "data:") == 0) {
      const std::size_t comma = raw.find(',', i);
      const std::size_t media_end = raw.find_first_of(";,", i);
      if (comma != std::string::npos && comma - i < 128) {
        std::size_t end = comma + 1;
        while (end < raw.size() && (std::isalnum(static_cast<unsigned char>(raw[end])) || raw[end] == '+' ||
                                    raw[end] == '/' || raw[end] == '='))
          ++end;
        s += raw.substr(i, media_end - i) + " URI of " + std::to_string(end - comma - 1) + " base64 characters";
        i = end;
        continue;
      }
    }
    s += raw[i++];
  }
  if (const std::size_t echo = s.find("; last read: "); echo != std::string::npos) s.erase(echo);
  s = one_line_message(s);
  constexpr std::size_t kMax = 200;
  if (s.size() > kMax) s = s.substr(0, kMax) + " ...";
  return s;
}

GltfCage parse_gltf_cage(std::span<const std::uint8_t> bytes, const std::string& path, const GltfSelection& selection) {
  if (bytes.size() > kMaxGltfFileBytes) throw CageError(path + ": more than a glTF reader takes (2 GiB)");
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_encoded, nullptr);
  tinygltf::Model m;
  std::string err, warn;
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  const std::string base = fs::path(path).parent_path().string();
  const auto length = static_cast<unsigned int>(bytes.size());
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&m, &err, &warn, bytes.data(), length, base)
             : loader.LoadASCIIFromString(&m, &err, &warn, reinterpret_cast<const char*>(bytes.data()), length, base);
  if (!ok) {
    if (!binary) damaged_data_uris(bytes, path);
    throw CageError(path + ": not a readable glTF 2.0 file (" + loader_message(err.empty() ? warn : err) + ")");
  }
  const Reader r(path, m);
  for (const std::string& e : m.extensionsRequired)
    if (e != "FB_ngon_encoding" && e != "KHR_materials_displacement")
      r.fail("extensionsRequired", "requires " + e + ", which Tessera does not read");

  GltfCage out;
  Cage& cage = out.cage;
  cage.name = path;
  cage.uv_v_down = true;
  if (!warn.empty()) cage.warnings.push_back(path + ": " + one_line_message(warn));
  auto rig = std::make_shared<CageRig>();
  read_nodes(r, m, *rig);
  read_skins(r, m, *rig);

  // The scene's roots: the chosen or default scene, else every node without a parent.
  std::vector<int> roots;
  if (selection.scene) {
    if (*selection.scene < 0 || *selection.scene >= int(m.scenes.size()))
      throw CageError(path + ": scene " + std::to_string(*selection.scene) + " does not exist (the file has " +
                      std::to_string(m.scenes.size()) + ")");
    roots = m.scenes[std::size_t(*selection.scene)].nodes;
  } else if (!m.scenes.empty()) {
    const int s = m.defaultScene >= 0 && m.defaultScene < int(m.scenes.size()) ? m.defaultScene : 0;
    roots = m.scenes[std::size_t(s)].nodes;
  } else {
    for (std::size_t n = 0; n < rig->nodes.size(); ++n)
      if (rig->nodes[n].parent < 0) roots.push_back(int(n));
  }
  // Depth first, parents before children; a node met twice is a cycle or a shared child.
  std::vector<bool> seen(rig->nodes.size(), false);
  std::function<void(int)> visit = [&](int n) {
    if (n < 0 || n >= int(rig->nodes.size())) r.fail("scene", "names node " + std::to_string(n) + ", which is missing");
    if (seen[std::size_t(n)]) r.fail(named("node", n, rig->nodes[std::size_t(n)].name), "is reached twice (a cycle)");
    if (rig->node_order.size() > rig->nodes.size()) r.fail("scene", "the node hierarchy is too deep");
    seen[std::size_t(n)] = true;
    rig->node_order.push_back(n);
    for (const int c : m.nodes[std::size_t(n)].children) visit(c);
  };
  for (const int n : roots) visit(n);

  bool any_selected = false, want_uvs = false, decided = false;
  std::vector<std::string> names;
  for (const int n : rig->node_order) {
    const tinygltf::Node& node = m.nodes[std::size_t(n)];
    if (node.mesh < 0) continue;
    if (node.mesh >= int(m.meshes.size()))
      r.fail(named("node", n, node.name), "draws mesh " + std::to_string(node.mesh) + ", which is missing");
    const tinygltf::Mesh& mesh = m.meshes[std::size_t(node.mesh)];
    names.push_back(mesh.name.empty() ? node.name : mesh.name);
    if (!selection.mesh.empty() && mesh.name != selection.mesh && node.name != selection.mesh) continue;
    if (node.skin >= int(rig->skins.size()))
      r.fail(named("node", n, node.name), "uses skin " + std::to_string(node.skin) + ", which is missing");
    RigInstance inst;
    inst.node = n;
    inst.skin = node.skin;
    inst.first_target = rig->target_count();
    inst.target_count = mesh.primitives.empty() ? 0 : int(mesh.primitives[0].targets.size());
    // Target names: the common mesh.extras.targetNames convention, else "target N".
    const tinygltf::Value& names_value = mesh.extras.IsObject() ? mesh.extras.Get("targetNames") : tinygltf::Value();
    for (int t = 0; t < inst.target_count; ++t) {
      rig->target_deltas.emplace_back();
      const bool has_name = names_value.IsArray() && t < int(names_value.ArrayLen()) && names_value.Get(t).IsString();
      rig->target_names.push_back(has_name ? names_value.Get(t).Get<std::string>() : "target " + std::to_string(t));
    }
    const int instance = int(rig->instances.size());
    rig->instances.push_back(inst);
    InstanceBuilder builder(r, m, cage, *rig, instance);
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) {
        cage.warnings.push_back(path + ": " + named("mesh", node.mesh, mesh.name) + " primitive " + std::to_string(p) +
                                ": mode " + std::to_string(prim.mode) + " is not triangles; skipped");
        continue;
      }
      if (!decided) {
        want_uvs = prim.attributes.count("TEXCOORD_0") > 0, decided = true;
        out.maps = material_maps(r, m, prim.material);
      }
      builder.add_primitive(node.mesh, int(p), want_uvs);
      any_selected = true;
    }
    out.gltf_vertices += builder.gltf_vertices;
  }
  if (!selection.mesh.empty() && rig->instances.empty()) {
    std::string list;
    for (const auto& s : names) list += (list.empty() ? "" : ", ") + s;
    throw CageError(path + ": no mesh or node named '" + selection.mesh +
                    "' (it has: " + (list.empty() ? "none" : list) + ")");
  }
  if (!any_selected || cage.face_sizes.empty())
    throw CageError(path + ": no triangles to read (no mesh primitive of mode 4 in the scene)");
  if (!rig->joints.empty())
    rig->joints.resize(rig->bind_positions.size(), {}), rig->weights.resize(rig->bind_positions.size(), {});
  for (auto& d : rig->target_deltas) d.resize(rig->bind_positions.size(), glm::vec3(0.0f));
  read_animations(r, m, *rig, cage.warnings);

  // The rest pose is the cage.
  const RigPose rest = rest_pose(*rig);
  cage.positions = pose_positions(*rig, rest);
  for (std::size_t v = 0; v < cage.positions.size(); ++v)
    if (!std::isfinite(cage.positions[v].x) || !std::isfinite(cage.positions[v].y) ||
        !std::isfinite(cage.positions[v].z))
      throw CageError(path + ": vertex " + std::to_string(v) +
                      " is not finite in the rest pose (node transforms overflow)");
  // Non-manifold places split as OpenSubdiv draws them; the copies move with the vertices they copy.
  if (!split_non_manifold(cage).empty()) rig->copy_vertices(cage.vertex_source);
  const bool moves = !rig->skins.empty() || rig->target_count() > 0 || !rig->animations.empty();
  if (moves) out.rig = std::move(rig);
  return out;
}

}  // namespace tessera
