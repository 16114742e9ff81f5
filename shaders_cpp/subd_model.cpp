#include "subd_model.h"

#include "cage_obj.h"
#include "pn_patch.h"

namespace tessera {

SubdModel make_subd_model(Cage cage, Scheme scheme) {
  SubdModel m;
  m.cage = std::move(cage);
  m.topology = std::make_unique<Topology>(m.cage);
  m.patches = build_patches(m.cage, *m.topology, scheme);
  if (scheme == Scheme::pn) m.normals = vertex_normals(m.cage, *m.topology);
  if (scheme == Scheme::exact) m.limit = std::make_unique<LimitSurface>(LimitSurface::create(m.cage));
  return m;
}

SubdModel load_subd_model(const std::string& path, Scheme scheme) { return make_subd_model(load_obj_cage(path), scheme); }

}  // namespace tessera
