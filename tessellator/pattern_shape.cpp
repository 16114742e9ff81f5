#include "tessellator/pattern_shape.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tessera::ts {

namespace {

struct Corner {
  double cubic, quartic, perimeter, product;
};

// The shape terms with `a` as the corner, scaled by 1 / area.
Corner corner_terms(const DomainPoint& a, const DomainPoint& b, const DomainPoint& c, double inverse_area) {
  const double s1 = double(b.u) - double(a.u), t1 = double(b.v) - double(a.v);
  const double s2 = double(c.u) - double(a.u), t2 = double(c.v) - double(a.v);
  const double l1 = std::abs(s1) + std::abs(t1), l2 = std::abs(s2) + std::abs(t2);
  return {l1 * l2 * (l1 + l2) * inverse_area, l1 * l1 * l2 * l2 * inverse_area, (l1 + l2) * inverse_area,
          l1 * l2 * inverse_area};
}

}  // namespace

PatternShape pattern_shape(const Pattern& pattern) {
  PatternShape shape;
  if (pattern.culled ||
      (pattern.output != OutputPrimitive::triangle_cw && pattern.output != OutputPrimitive::triangle_ccw))
    return shape;
  const auto& p = pattern.points;
  const auto& idx = pattern.indices;
  int sign = 0;
  for (std::size_t i = 0; i + 2 < idx.size(); i += 3) {
    const DomainPoint& a = p[idx[i]];
    const DomainPoint& b = p[idx[i + 1]];
    const DomainPoint& c = p[idx[i + 2]];
    // Exact in double: the differences of floats and their products fit in 53 bits.
    const double area = (double(b.u) - double(a.u)) * (double(c.v) - double(a.v)) -
                        (double(b.v) - double(a.v)) * (double(c.u) - double(a.u));
    const int s = area > 0 ? 1 : area < 0 ? -1 : 0;
    if (s == 0 || (sign != 0 && s != sign)) return PatternShape{};
    sign = s;
    const double inverse = (1.0 / std::abs(area)) * (1.0 + 0x1p-40);
    const std::array<Corner, 3> corners = {corner_terms(a, b, c, inverse), corner_terms(b, c, a, inverse),
                                           corner_terms(c, a, b, inverse)};
    const Corner& best = *std::min_element(corners.begin(), corners.end(),
                                           [](const Corner& x, const Corner& y) { return x.cubic < y.cubic; });
    constexpr double up = 1.0 + 0x1p-40;
    shape.cubic = std::max(shape.cubic, best.cubic * up);
    shape.quartic = std::max(shape.quartic, best.quartic * up);
    shape.perimeter = std::max(shape.perimeter, best.perimeter * up);
    shape.product = std::max(shape.product, best.product * up);
    shape.inverse = std::max(shape.inverse, inverse);
  }
  if (sign == 0) return PatternShape{};
  shape.consistent = true;
  shape.orientation = sign;
  return shape;
}

}  // namespace tessera::ts
