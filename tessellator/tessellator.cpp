// Dispatch from processed factors to the domains, the minimal cases, names and hashing.
#include "tessellator/tessellator.h"

#include "tessellator/domains.h"
#include "tessellator/fnv1a.h"
#include "tessellator/stitch.h"

namespace tessera::ts {

int Pattern::vertices_per_primitive() const {
  switch (output) {
    case OutputPrimitive::point: return 1;
    case OutputPrimitive::line: return 2;
    case OutputPrimitive::triangle_cw:
    case OutputPrimitive::triangle_ccw: break;
  }
  return domain == Domain::isoline ? 2 : 3;  // isolines only ever make segments
}

void Pattern::clear() {
  culled = false;
  points.clear();
  indices.clear();
}

namespace {

// The reference's debugging output for lines on tri/quad domains: consecutive points linked.
void in_order_line_list(Pattern& out) {
  for (std::uint32_t i = 1; i < out.points.size(); ++i) {
    out.indices.push_back(i - 1);
    out.indices.push_back(i);
  }
}

void all_points(Pattern& out) {
  for (std::uint32_t i = 0; i < out.points.size(); ++i) out.indices.push_back(i);
}

}  // namespace

void generate(const ProcessedFactors& p, OutputPrimitive output, Pattern& out) {
  out.clear();
  out.output = output;
  out.domain = p.domain;
  if (p.culled) {
    out.culled = true;
    return;
  }
  if (p.domain == Domain::isoline) {
    detail::isoline_generate(p, output, out);
    return;
  }
  const bool ccw = output == OutputPrimitive::triangle_ccw;
  detail::TriangleWriter writer(out.indices, ccw);
  if (p.minimal) {
    if (p.domain == Domain::quad) {
      out.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      if (output == OutputPrimitive::triangle_cw || ccw) {
        writer.clockwise(0, 1, 3);
        writer.clockwise(1, 2, 3);
      }
    } else {
      out.points = {{0, 1}, {0, 0}, {1, 0}};  // the starts of edges Ueq0, Veq0, Weq0
      if (output == OutputPrimitive::triangle_cw || ccw) writer.clockwise(0, 1, 2);
    }
  } else if (p.domain == Domain::quad) {
    detail::quad_generate_points(p, out.points);
    if (output == OutputPrimitive::triangle_cw || ccw) detail::quad_generate_connectivity(p, ccw, out.indices);
  } else {
    detail::tri_generate_points(p, out.points);
    if (output == OutputPrimitive::triangle_cw || ccw) detail::tri_generate_connectivity(p, ccw, out.indices);
  }
  if (output == OutputPrimitive::point) all_points(out);
  if (output == OutputPrimitive::line) in_order_line_list(out);
}

void tessellate_quad(Partitioning partitioning, OutputPrimitive output, const QuadFactors& f, Pattern& out) {
  generate(process_quad_factors(partitioning, f), output, out);
}
void tessellate_tri(Partitioning partitioning, OutputPrimitive output, const TriFactors& f, Pattern& out) {
  generate(process_tri_factors(partitioning, f), output, out);
}
void tessellate_isoline(Partitioning partitioning, OutputPrimitive output, const IsolineFactors& f, Pattern& out) {
  generate(process_isoline_factors(partitioning, f), output, out);
}
void tessellate(Partitioning partitioning, OutputPrimitive output, const FactorSet& f, Pattern& out) {
  generate(process_factors(partitioning, f), output, out);
}

int outer_factor_count(Domain d) { return d == Domain::quad ? 4 : d == Domain::tri ? 3 : 2; }
int inside_factor_count(Domain d) { return d == Domain::quad ? 2 : d == Domain::tri ? 1 : 0; }

namespace {

// The fields that determine a pattern; the rest of an EdgeContext derives from them.
void add(Fnv1a& h, const EdgeContext& c) {
  h.add(c.factor);
  h.add(static_cast<std::uint64_t>(c.parity));
  h.add(static_cast<std::uint64_t>(c.num_points));
}

}  // namespace

std::uint64_t hash(const ProcessedFactors& p, OutputPrimitive output) {
  Fnv1a h;
  h.add(static_cast<std::uint64_t>(p.domain) | std::uint64_t(p.culled) << 8 | std::uint64_t(p.minimal) << 9 |
        static_cast<std::uint64_t>(output) << 16);
  for (const auto& c : p.outside) add(h, c);
  for (const auto& c : p.inside) add(h, c);
  return h.value;
}

std::string_view to_string(Domain d) {
  switch (d) {
    case Domain::quad: return "quad";
    case Domain::tri: return "tri";
    case Domain::isoline: return "isoline";
  }
  return "?";
}
std::string_view to_string(Partitioning p) {
  switch (p) {
    case Partitioning::integer: return "integer";
    case Partitioning::pow2: return "pow2";
    case Partitioning::fractional_odd: return "fractional_odd";
    case Partitioning::fractional_even: return "fractional_even";
  }
  return "?";
}
std::string_view to_string(OutputPrimitive o) {
  switch (o) {
    case OutputPrimitive::point: return "point";
    case OutputPrimitive::line: return "line";
    case OutputPrimitive::triangle_cw: return "triangle_cw";
    case OutputPrimitive::triangle_ccw: return "triangle_ccw";
  }
  return "?";
}
std::optional<Domain> parse_domain(std::string_view s) {
  for (Domain d : {Domain::quad, Domain::tri, Domain::isoline})
    if (s == to_string(d)) return d;
  return std::nullopt;
}
std::optional<Partitioning> parse_partitioning(std::string_view s) {
  for (Partitioning p :
       {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd, Partitioning::fractional_even})
    if (s == to_string(p)) return p;
  return std::nullopt;
}
std::optional<OutputPrimitive> parse_output_primitive(std::string_view s) {
  for (OutputPrimitive o :
       {OutputPrimitive::point, OutputPrimitive::line, OutputPrimitive::triangle_cw, OutputPrimitive::triangle_ccw})
    if (s == to_string(o)) return o;
  return std::nullopt;
}

}  // namespace tessera::ts
