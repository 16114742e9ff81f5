// STOPGAP, test-only: a minimal OBJ reader for the limit-surface tests, to be replaced by
// load_obj_cage (shaders_cpp/cage_obj.h) once it lands. It reads `v`, `f` (first index of each
// `a/b/c`, 1-based or negative) and the OpenSubdiv tag lines `t crease|corner|hole|
// interpolateboundary|creasemethod|smoothtriangles`; everything else is ignored. No validation.
#pragma once

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cage.h"

namespace tessera::test {

inline std::string osd_shape(const std::string& name) { return std::string(TESSERA_TEST_DATA_DIR) + "/osd-shapes/" + name + ".obj"; }
inline std::string sdk_cage(const std::string& name) { return std::string(TESSERA_TEST_DATA_DIR) + "/sdk-cages/" + name + ".obj"; }

inline Cage read_test_cage(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  Cage c;
  c.name = path;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    std::string kw;
    ss >> kw;
    if (kw == "v") {
      glm::vec3 p;
      ss >> p.x >> p.y >> p.z;
      c.positions.push_back(p);
    } else if (kw == "f") {
      c.face_offsets.push_back(int(c.face_vertices.size()));
      std::string tok;
      int n = 0;
      while (ss >> tok) {
        const int i = std::stoi(tok.substr(0, tok.find('/')));
        c.face_vertices.push_back(i > 0 ? i - 1 : int(c.positions.size()) + i);
        ++n;
      }
      c.face_sizes.push_back(n);
    } else if (kw == "t") {
      std::string name, counts;
      ss >> name >> counts;
      int ni = 0, nf = 0, ns = 0;
      char slash;
      std::istringstream cs(counts);
      cs >> ni >> slash >> nf >> slash >> ns;
      std::vector<int> ints(static_cast<std::size_t>(ni));
      std::vector<float> floats(static_cast<std::size_t>(nf));
      std::vector<std::string> strings(static_cast<std::size_t>(ns));
      for (auto& x : ints) ss >> x;
      for (auto& x : floats) ss >> x;
      for (auto& x : strings) ss >> x;
      if (name == "crease")
        for (int k = 0; k + 1 < ni; ++k) c.tags.creases.push_back({ints[std::size_t(k)], ints[std::size_t(k) + 1], floats[nf > 1 ? std::size_t(k) : 0]});
      else if (name == "corner")
        for (int k = 0; k < ni; ++k) c.tags.corners.push_back({ints[std::size_t(k)], floats[nf > 1 ? std::size_t(k) : 0]});
      else if (name == "hole")
        c.tags.holes.insert(c.tags.holes.end(), ints.begin(), ints.end());
      else if (name == "interpolateboundary" && ni > 0)
        c.tags.boundary = ints[0] == 0 ? BoundaryInterpolation::none
                          : ints[0] == 1 ? BoundaryInterpolation::edge_and_corner
                                         : BoundaryInterpolation::edge_only;
      else if (name == "creasemethod" && ns > 0)
        c.tags.crease_method = strings[0] == "chaikin" ? CreaseMethod::chaikin : CreaseMethod::uniform;
      else if (name == "smoothtriangles" && ns > 0)
        c.tags.smooth_triangles = strings[0] == "smooth";
    }
  }
  return c;
}

}  // namespace tessera::test
