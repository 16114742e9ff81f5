// Accuracy of a LimitSurface: against OpenSubdiv's exact vertex limits at uniformly refined vertices
// (exact_limit_samples), or against another LimitSurface of the same cage.
#include "tools/measure/limit_accuracy.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "shaders_cpp/subdiv/exact_limit_samples.h"

namespace tessera::measure {

LimitAccuracy measure_limit_accuracy(const Cage& cage, const LimitSurface& surface, int refine_level) {
  std::vector<bool> faces(std::size_t(cage.face_count()), false);
  for (int f = 0; f < cage.face_count(); ++f) faces[std::size_t(f)] = surface.has_surface(f);
  const std::vector<ExactLimitSample> exact = exact_limit_samples(cage, faces, refine_level);
  LimitAccuracy acc;
  acc.diagonal = surface.bounding_box_diagonal();
  double sum2 = 0;
  for (const ExactLimitSample& s : exact) {
    const double d = glm::length(surface.sample_reference(s.face, s.sub_patch, s.uv.x, s.uv.y).position - s.position);
    acc.max_distance = std::max(acc.max_distance, d);
    sum2 += d * d;
    ++acc.samples;
  }
  acc.rms_distance = acc.samples ? std::sqrt(sum2 / double(acc.samples)) : 0.0;
  return acc;
}

LimitAccuracy compare_limit_surfaces(const LimitSurface& a, const LimitSurface& b, int rate) {
  if (a.face_count() != b.face_count()) throw std::invalid_argument("compare_limit_surfaces: different cages");
  if (rate < 1) throw std::invalid_argument("compare_limit_surfaces: rate must be positive");
  LimitAccuracy acc;
  acc.diagonal = b.bounding_box_diagonal();
  double sum2 = 0;
  const auto sample = [&](int f, int k, double u, double v) {
    const double d = glm::length(a.sample_reference(f, k, u, v).position - b.sample_reference(f, k, u, v).position);
    acc.max_distance = std::max(acc.max_distance, d);
    sum2 += d * d;
    ++acc.samples;
  };
  for (int f = 0; f < a.face_count(); ++f)
    for (int k = 0; k < std::min(a.sub_patch_count(f), b.sub_patch_count(f)); ++k) {
      for (int i = 0; i <= rate; ++i)
        for (int j = 0; j <= rate; ++j) sample(f, k, double(i) / rate, double(j) / rate);
      // Zoom into every corner: an approximation at level L differs from the limit only within
      // ~2^-L of an extraordinary vertex, which a uniform grid never reaches.
      for (int m = 1; m <= 12; ++m)
        for (int i = 1; i <= 3; ++i)
          for (int j = 1; j <= 3; ++j) {
            const double u = std::ldexp(i / 3.7, -m), v = std::ldexp(j / 3.7, -m);
            sample(f, k, u, v);
            sample(f, k, 1 - u, v);
            sample(f, k, u, 1 - v);
            sample(f, k, 1 - u, 1 - v);
          }
    }
  acc.rms_distance = acc.samples ? std::sqrt(sum2 / double(acc.samples)) : 0.0;
  return acc;
}

}  // namespace tessera::measure
