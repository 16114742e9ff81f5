#include "shaders_cpp/displacement/watertight_uv.h"

#include <string>

namespace tessera {

int edge_owner(const Topology& t, int h) {
  const int twin = t.twin(h);
  if (twin < 0 || t.is_hole(t.face(twin))) return h;
  if (t.is_hole(t.face(h))) return twin;
  return h < twin ? h : twin;
}

int vertex_owner(const Topology& t, int v) {
  int owner = -1;
  for (int h : t.ring(v))
    if (!t.is_hole(t.face(h)) && (owner < 0 || h < owner)) owner = h;
  return owner;
}

std::vector<PatchTexcoords> build_patch_texcoords(const Cage& cage, const Topology& t, const PatchGroup& group,
                                                  UvOwnership ownership, bool flip_v, const UvTiles* tiles) {
  if (!cage.has_uvs()) throw CageError(cage.name + ": has no texture coordinates (vt); a displacement map needs them");
  for (int f = 0; f < t.face_count(); ++f)
    if (!t.is_hole(f) && t.face_size(f) != 4)
      throw CageError(cage.name + ": face " + std::to_string(f) + " has " + std::to_string(t.face_size(f)) +
                      " sides; displacement handles quad faces only");
  // UV of corner k (mod 4) of face f.
  std::vector<glm::vec2> uvs = cage.uvs;
  if (flip_v && tiles == nullptr)
    for (auto& x : uvs) x.y = 1.0f - x.y;
  auto tile = [&](int f) { return tiles != nullptr ? tiles->face_tile[std::size_t(f)] : std::uint16_t(0); };
  auto uv = [&](int f, int k) {
    const glm::vec2 x = uvs[std::size_t(cage.face_uvs[std::size_t(t.face_offset(f) + ((k % 4) + 4) % 4)])];
    return tiles != nullptr ? tiles->local(x, tile(f), !flip_v) : x;  // UvTiles::local flips it
  };
  // Twice the signed area of face f's UV quad: its chart's orientation.
  auto uv_area = [&](int f) {
    double a = 0.0;
    for (int k = 0; k < 4; ++k) {
      const glm::vec2 p = uv(f, k), q = uv(f, k + 1);
      a += double(p.x) * double(q.y) - double(q.x) * double(p.y);
    }
    return a;
  };
  std::vector<PatchTexcoords> out;
  out.reserve(group.size());
  for (const SubdPatch& p : group.patches) {
    PatchTexcoords tc;
    const int f = p.face;
    for (int k = 0; k < 4; ++k) {
      const int fk = k + p.rotation;  // face corner of patch corner k
      tc.tile = tile(f);
      tc.interior[std::size_t(k)] = uv(f, fk);
      const int h = t.face_offset(f) + fk % 4;
      // Edge k: from patch corner k to k + 1, the face's half-edge h.
      const int ho = edge_owner(t, h);
      const int fo = t.face(ho), co = t.corner(ho);
      tc.edge[std::size_t(k)] = {uv(fo, co), uv(fo, co + 1), uv(fo, co + 2), uv(fo, co + 3)};
      tc.reversed[std::size_t(k)] = ho != h;
      tc.edge_tile[std::size_t(k)] = tile(fo);
      if (ownership == UvOwnership::per_face) {
        tc.edge_tile[std::size_t(k)] = tile(f);
        // The naive way: this face's own UVs (still in the owner's direction, which the frames use).
        const glm::vec2 a = uv(f, fk), b = uv(f, fk + 1), c = uv(f, fk + 2), d = uv(f, fk + 3);
        tc.edge[std::size_t(k)] = ho == h ? std::array<glm::vec2, 4>{a, b, c, d} : std::array<glm::vec2, 4>{b, a, d, c};
      }
      tc.edge_face[std::size_t(k)] = fo, tc.edge_corner[std::size_t(k)] = std::uint8_t(co);
      // The face across edge k: its half-edge runs k + 1 -> k.
      const int ht = t.twin(h);
      tc.twin[std::size_t(k)] = {uv(f, fk), uv(f, fk + 1)};
      tc.twin_tile[std::size_t(k)] = tile(f);
      if (ht >= 0 && !t.is_hole(t.face(ht))) {
        const int ft = t.face(ht), ct = t.corner(ht);
        const glm::vec2 a = uv(ft, ct + 1), b = uv(ft, ct);
        if (a != uv(f, fk) || b != uv(f, fk + 1) || tile(ft) != tile(f)) {
          tc.twin[std::size_t(k)] = {a, b};
          tc.twin_tile[std::size_t(k)] = tile(ft);
          tc.seam_edges |= std::uint8_t(1u << k);
          if ((uv_area(f) < 0.0) != (uv_area(ft) < 0.0)) tc.twin_mirrored |= std::uint8_t(1u << k);
        }
      }
      // Corner k: the vertex at h's origin.
      const int hv = vertex_owner(t, t.origin(h));
      const int fv = t.face(hv), cv = t.corner(hv);
      tc.corner[std::size_t(k)] = ownership == UvOwnership::owned ? uv(fv, cv) : uv(f, fk);
      tc.corner_tile[std::size_t(k)] = ownership == UvOwnership::owned ? tile(fv) : tile(f);
      tc.vertex_face[std::size_t(k)] = fv, tc.vertex_corner[std::size_t(k)] = std::uint8_t(cv);
      tc.corner_span[std::size_t(k)] = {uv(fv, cv + 1) - uv(fv, cv), uv(fv, cv + 3) - uv(fv, cv)};
      tc.corner_key[std::size_t(k)] = cage_edge_key(t.origin(hv), t.destination(hv));
    }
    out.push_back(tc);
  }
  return out;
}

}  // namespace tessera
