// The adaptive scheme: feature-adaptive patches through Far, single-crease patches
// evaluated here (single_crease_basis.h), Gregory end caps; exact on regular and single-crease
// regions, converging to the limit as the isolation level rises, watertight to the bit.
#include <catch2/catch.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>
#include <vector>

#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/subdiv/limit_surface.h"
#include "shaders_cpp/subdiv/single_crease_basis.h"
#include "test_data.h"

using namespace tessera;
using tessera::test::data;
namespace {

std::string osd_shape(const std::string& name) { return data("osd-shapes/" + name + ".obj"); }

// 1D subdivision of four points across a crease on point 2, `steps` times towards x (the reference the
// closed form must equal): the crease vertex rule while sharpness is left, then smooth.
double subdivided_curve(const double q[4], double sharpness, double x, int steps) {
  double p[4] = {q[0], q[1], q[2], q[3]};
  double left = sharpness;
  for (int i = 0; i < steps; ++i) {
    const double sharp = std::clamp(left, 0.0, 1.0);
    const double n[5] = {0.5 * (p[0] + p[1]), (p[0] + 6 * p[1] + p[2]) / 8, 0.5 * (p[1] + p[2]),
                         (1 - sharp) * (p[1] + 6 * p[2] + p[3]) / 8 + sharp * p[2], 0.5 * (p[2] + p[3])};
    const int first = x < 0.5 ? 0 : 1;
    // Past the crease's span the crease vertex is no longer in this span's points: no rule to follow.
    if (first == 0) left = 0.0;
    for (int k = 0; k < 4; ++k) p[k] = n[first + k];
    x = first == 0 ? 2 * x : 2 * x - 1;
    left -= 1.0;
  }
  double w[4], dw[4];
  subdiv::cubic_bspline_basis(x, w, dw);
  return w[0] * p[0] + w[1] * p[1] + w[2] * p[2] + w[3] * p[3];
}

double curve(const double q[4], double sharpness, double x) {
  double w[4], dw[4];
  subdiv::crease_curve_basis(x, sharpness, w, dw);
  return w[0] * q[0] + w[1] * q[1] + w[2] * q[2] + w[3] * q[3];
}

double max_distance(const LimitSurface& a, const LimitSurface& b, int n) {
  double worst = 0.0;
  for (int f = 0; f < a.face_count(); ++f)
    for (int k = 0; k < a.sub_patch_count(f); ++k)
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
          const float u = float(i) / float(n), v = float(j) / float(n);
          worst = std::max(worst, double(glm::length(a.evaluate_unowned(f, k, u, v).position -
                                                     b.evaluate_unowned(f, k, u, v).position)));
        }
  return worst / b.bounding_box_diagonal();
}

}  // namespace

TEST_CASE("adaptive: the crease curve is the subdivision it stands for", "[adaptive]") {
  const double q[4] = {0.3, -1.1, 2.0, 0.7};
  for (const double sharpness : {0.0, 0.4, 1.0, 1.5, 2.0, 2.8, 5.7}) {
    INFO("sharpness " << sharpness);
    double sum_at = 0.0;
    for (int i = 0; i <= 64; ++i) {
      const double x = i / 64.0;
      // 40 steps: the smooth tail's B-spline segment is 2^-40 long, its variation below round-off.
      CHECK(curve(q, sharpness, x) == Approx(subdivided_curve(q, sharpness, x, 40)).margin(1e-9));
      double w[4], dw[4];
      subdiv::crease_curve_basis(x, sharpness, w, dw);
      sum_at = w[0] + w[1] + w[2] + w[3];
      CHECK(sum_at == Approx(1.0).margin(1e-14));
      CHECK(dw[0] + dw[1] + dw[2] + dw[3] == Approx(0.0).margin(1e-12));
      // The derivative is the curve's: central differences away from the span joints.
      const double h = 1e-6;
      if (x > h && x < 1 - h) {
        const double fd = (curve(q, sharpness, x + h) - curve(q, sharpness, x - h)) / (2 * h);
        CHECK(dw[0] * q[0] + dw[1] * q[1] + dw[2] * q[2] + dw[3] * q[3] == Approx(fd).margin(1e-5));
      }
    }
  }
  // Sharpness 0 is the B-spline; a high sharpness interpolates the crease point.
  double w[4], dw[4], b[4], db[4];
  subdiv::crease_curve_basis(0.3, 0.0, w, dw);
  subdiv::cubic_bspline_basis(0.3, b, db);
  for (int k = 0; k < 4; ++k) CHECK(w[k] == b[k]);
  subdiv::crease_curve_basis(1.0, 30.0, w, dw);
  CHECK(w[2] == Approx(1.0).margin(1e-8));
}

TEST_CASE("adaptive: exact on regular and single-crease regions, converging with the isolation level",
          "[adaptive]") {
  // catmark_single_crease: a regular grid with creases of sharpness 0.2 .. 5.7 and infinite; at level 6
  // no sharpness is capped, and every patch is regular, boundary or single-crease except at its corners.
  const Cage single = load_obj_cage(osd_shape("catmark_single_crease"));
  const LimitSurface exact = LimitSurface::create(single);
  const LimitSurface l6 = LimitSurface::create_adaptive(single, 6);
  CHECK(l6.adaptive());
  CHECK(l6.approx_level() == 6);
  const LimitSurface::PatchCounts c = l6.patch_counts();
  CHECK(c.by_kind[int(AdaptivePatchKind::single_crease)] > 0);
  CHECK(c.total == c.by_kind[0] + c.by_kind[1] + c.by_kind[2] + c.by_kind[3]);
  CHECK(max_distance(l6, exact, 8) < 1e-6);
  // Capped at level 2 the sharpness-5.7 crease is drawn as 2: visibly not the limit.
  CHECK(max_distance(LimitSurface::create_adaptive(single, 2), exact, 8) > 1e-3);

  for (const char* name : {"catmark_cube_creases1", "catmark_cubes_semisharp", "catmark_cube_corner4"}) {
    INFO(name);
    const Cage cage = load_obj_cage(osd_shape(name));
    const LimitSurface reference = LimitSurface::create(cage);
    const double e2 = max_distance(LimitSurface::create_adaptive(cage, 2), reference, 8);
    const double e4 = max_distance(LimitSurface::create_adaptive(cage, 4), reference, 8);
    const double e6 = max_distance(LimitSurface::create_adaptive(cage, 6), reference, 8);
    CHECK(e4 <= e2 + 1e-7);  // (smooth shapes reach round-off at once)
    CHECK(e6 <= e4 + 1e-7);
    CHECK(e6 < 1e-3);
  }
}

TEST_CASE("adaptive: derivatives are those of the surface, on n-gons too", "[adaptive]") {
  // Central differences of the position against the reported du, dv: on a pentagon's sub-patches (the
  // derivative's scale there is the sub-patch's own, as Bfr's) and across single-crease patches.
  for (const char* name : {"catmark_nonquads", "catmark_single_crease"}) {
    INFO(name);
    const LimitSurface s = LimitSurface::create_adaptive(load_obj_cage(osd_shape(name)), 4);
    const float h = 1.0f / 1024.0f;
    double worst = 0.0, scale = 0.0;
    for (int f = 0; f < s.face_count(); ++f)
      for (int k = 0; k < s.sub_patch_count(f); ++k)
        for (const float u : {0.3f, 0.55f, 0.8f})
          for (const float v : {0.2f, 0.45f, 0.7f}) {
            const SurfacePoint p = s.evaluate_unowned(f, k, u, v);
            const glm::vec3 fu =
                (s.evaluate_unowned(f, k, u + h, v).position - s.evaluate_unowned(f, k, u - h, v).position) / (2 * h);
            const glm::vec3 fv =
                (s.evaluate_unowned(f, k, u, v + h).position - s.evaluate_unowned(f, k, u, v - h).position) / (2 * h);
            worst = std::max({worst, double(glm::length(fu - p.du)), double(glm::length(fv - p.dv))});
            scale = std::max({scale, double(glm::length(p.du)), double(glm::length(p.dv))});
          }
    CHECK(worst < 2e-3 * scale);
  }
}

TEST_CASE("adaptive: isolation levels outside 1..10 are refused", "[adaptive]") {
  const Cage cage = load_obj_cage(osd_shape("catmark_cube"));
  CHECK_THROWS_AS(LimitSurface::create_adaptive(cage, 0), std::invalid_argument);
  CHECK_THROWS_AS(LimitSurface::create_adaptive(cage, kMaxIsolation + 1), std::invalid_argument);
  CHECK_THROWS_AS(LimitSurface::create(cage).patch_counts(), std::logic_error);
}
