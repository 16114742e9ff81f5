#include "tools/verify/oracle.h"

#include "tessellator/fnv1a.h"

#include <algorithm>
#include <bit>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace tessera::oracle {
namespace {

const char* gl_domain(ts::Domain d) {
  return d == ts::Domain::quad ? "quads" : d == ts::Domain::tri ? "triangles" : "isolines";
}
// A number in a capture or case line: strtof over the whole token (the harness prints %.9g).
bool read_capture_float(const std::string& s, float& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtof(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

Primitive canonical(Primitive p) {
  if (p.size() == 2) {
    std::sort(p.begin(), p.end());
  } else if (p.size() == 3) {
    const auto smallest = std::min_element(p.begin(), p.end());
    std::rotate(p.begin(), smallest, p.end());
  }
  return p;
}

// Digests hash each coordinate's 4 bytes, with a separator after each primitive.
void add(ts::Fnv1a& h, const std::vector<Primitive>& prims) {
  for (const auto& p : prims) {
    for (const auto& v : p)
      for (auto c : v) h.add(c, 4);
    h.add(0xFFFFFFFFu, 4);
  }
}

std::string vertex_string(const Vertex& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%a, %a, %a)", double(std::bit_cast<float>(v[0])), double(std::bit_cast<float>(v[1])),
                double(std::bit_cast<float>(v[2])));
  return buf;
}

}  // namespace

const char* gl_spacing(ts::Partitioning p) {
  switch (p) {
    case ts::Partitioning::integer:
    case ts::Partitioning::pow2: return "equal_spacing";
    case ts::Partitioning::fractional_odd: return "fractional_odd_spacing";
    case ts::Partitioning::fractional_even: return "fractional_even_spacing";
  }
  return "equal_spacing";
}

bool parse_case_line(const std::string& line, Case& out, std::string& error) {
  std::istringstream in(line);
  std::string domain, spacing, winding, mode, f[6];
  in >> domain >> spacing >> winding >> mode;
  for (auto& x : f) in >> x;
  std::string extra;
  if (!in || (in >> extra)) {
    error = "expected 'DOMAIN SPACING WINDING MODE O0 O1 O2 O3 I0 I1'";
    return false;
  }
  out = Case{};
  out.line = line;
  if (domain == "quads")
    out.factors.domain = ts::Domain::quad;
  else if (domain == "triangles")
    out.factors.domain = ts::Domain::tri;
  else if (domain == "isolines")
    out.factors.domain = ts::Domain::isoline;
  else
    return error = "unknown domain '" + domain + "'", false;
  if (spacing == "equal_spacing")
    out.partitioning = ts::Partitioning::integer;
  else if (spacing == "fractional_odd_spacing")
    out.partitioning = ts::Partitioning::fractional_odd;
  else if (spacing == "fractional_even_spacing")
    out.partitioning = ts::Partitioning::fractional_even;
  else
    return error = "unknown spacing '" + spacing + "'", false;
  if (winding != "ccw" && winding != "cw") return error = "unknown winding '" + winding + "'", false;
  if (mode != "prims" && mode != "points") return error = "unknown mode '" + mode + "'", false;
  if (mode == "points")
    out.output = ts::OutputPrimitive::point;
  else if (out.factors.domain == ts::Domain::isoline)
    out.output = ts::OutputPrimitive::line;
  else
    out.output = winding == "ccw" ? ts::OutputPrimitive::triangle_cw : ts::OutputPrimitive::triangle_ccw;
  float v[6];
  for (int i = 0; i < 6; ++i)
    if (!read_capture_float(f[i], v[i])) return error = "bad factor '" + f[i] + "'", false;
  switch (out.factors.domain) {
    case ts::Domain::quad: out.factors.values = {v[0], v[1], v[2], v[3], v[4], v[5]}; break;
    case ts::Domain::tri: out.factors.values = {v[0], v[1], v[2], v[4], 0, 0}; break;
    case ts::Domain::isoline: out.factors.values = {v[0], v[1], 0, 0, 0, 0}; break;
  }
  return true;
}

std::string case_line(ts::Domain d, ts::Partitioning p, ts::OutputPrimitive o, const std::array<float, 6>& x) {
  std::array<float, 6> gl{};  // O0 O1 O2 O3 I0 I1
  switch (d) {
    case ts::Domain::quad: gl = x; break;
    case ts::Domain::tri: gl = {x[0], x[1], x[2], 1, x[3], 1}; break;
    case ts::Domain::isoline: gl = {x[0], x[1], 1, 1, 1, 1}; break;
  }
  std::string s = std::string(gl_domain(d)) + " " + gl_spacing(p) + " " +
                  (o == ts::OutputPrimitive::triangle_ccw ? "cw" : "ccw") + " " +
                  (o == ts::OutputPrimitive::point ? "points" : "prims");
  for (float f : gl) {
    char buf[32];
    std::snprintf(buf, sizeof buf, " %.9g", double(f));
    s += buf;
  }
  return s;
}

bool read_dump(std::istream& in, std::vector<Capture>& out, std::string& error) {
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.rfind("case ", 0) != 0) continue;
    Capture cap;
    std::string why;
    if (!parse_case_line(line.substr(5), cap.c, why))
      return error = "line " + std::to_string(line_no) + ": " + why, false;
    if (!std::getline(in, line))
      return error = "line " + std::to_string(line_no) + ": case without a count line", false;
    ++line_no;
    unsigned long n = 0;
    int per = 0;
    if (std::sscanf(line.c_str(), "n %lu per %d", &n, &per) != 2 || per < 1 || per > 3)
      return error = "line " + std::to_string(line_no) + ": expected 'n <count> per <1|2|3>'", false;
    cap.primitives.resize(n);
    for (auto& prim : cap.primitives) {
      prim.resize(std::size_t(per));
      for (auto& v : prim) {
        if (!std::getline(in, line))
          return error = "line " + std::to_string(line_no) + ": dump ends inside a case", false;
        ++line_no;
        std::istringstream vs(line);
        std::string a, b, c;
        float fa, fb, fc;
        vs >> a >> b >> c;
        if (!read_capture_float(a, fa) || !read_capture_float(b, fb) || !read_capture_float(c, fc))
          return error = "line " + std::to_string(line_no) + ": expected three hex floats", false;
        v = {std::bit_cast<std::uint32_t>(fa), std::bit_cast<std::uint32_t>(fb), std::bit_cast<std::uint32_t>(fc)};
      }
    }
    out.push_back(std::move(cap));
  }
  return true;
}

std::vector<Primitive> tessera_primitives(const Case& c) {
  ts::Pattern pattern;
  ts::tessellate(c.partitioning, c.output, c.factors, pattern);
  std::vector<Primitive> prims;
  const int per = pattern.vertices_per_primitive();
  prims.reserve(pattern.primitive_count());
  for (std::size_t i = 0; i + std::size_t(per) <= pattern.indices.size(); i += std::size_t(per)) {
    Primitive p;
    for (int k = 0; k < per; ++k) {
      const ts::DomainPoint d = pattern.points[pattern.indices[i + std::size_t(k)]];
      const float w = c.factors.domain == ts::Domain::tri ? (1.0f - d.u) - d.v : 0.0f;
      p.push_back(
          {std::bit_cast<std::uint32_t>(d.u), std::bit_cast<std::uint32_t>(d.v), std::bit_cast<std::uint32_t>(w)});
    }
    prims.push_back(std::move(p));
  }
  return prims;
}

Digest digest(const std::vector<Primitive>& prims) {
  Digest d;
  d.primitives = prims.size();
  ts::Fnv1a ordered;
  add(ordered, prims);
  d.ordered = ordered.value;
  std::vector<Primitive> canon;
  canon.reserve(prims.size());
  for (const auto& p : prims) canon.push_back(canonical(p));
  std::sort(canon.begin(), canon.end());
  ts::Fnv1a set;
  add(set, canon);
  d.set = set.value;
  return d;
}

Comparison compare(const std::vector<Primitive>& reference, const std::vector<Primitive>& ours) {
  Comparison r;
  r.order_equal = reference == ours;
  std::vector<Primitive> a, b;
  for (const auto& p : reference) a.push_back(canonical(p));
  for (const auto& p : ours) b.push_back(canonical(p));
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  r.set_equal = a == b;
  if (!r.set_equal) {
    std::ostringstream s;
    s << "reference has " << a.size() << " primitives, tessera " << b.size();
    std::vector<Primitive> only_ref, only_ours;
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(only_ref));
    std::set_difference(b.begin(), b.end(), a.begin(), a.end(), std::back_inserter(only_ours));
    if (!only_ref.empty()) {
      s << "; first only in reference:";
      for (const auto& v : only_ref.front()) s << " " << vertex_string(v);
    }
    if (!only_ours.empty()) {
      s << "; first only in tessera:";
      for (const auto& v : only_ours.front()) s << " " << vertex_string(v);
    }
    r.detail = s.str();
  } else if (!r.order_equal) {
    r.detail = "same primitives, different order";
  }
  return r;
}

std::string golden_line(const Case& c, const Digest& d) {
  char buf[96];
  std::snprintf(buf, sizeof buf, " => %zu %016" PRIx64 " %016" PRIx64, d.primitives, d.ordered, d.set);
  return c.line + buf;
}

bool parse_golden_line(const std::string& line, Case& c, Digest& d, std::string& error) {
  const auto arrow = line.find(" => ");
  if (arrow == std::string::npos) return error = "missing ' => '", false;
  if (!parse_case_line(line.substr(0, arrow), c, error)) return false;
  if (std::sscanf(line.c_str() + arrow + 4, "%zu %" SCNx64 " %" SCNx64, &d.primitives, &d.ordered, &d.set) != 3)
    return error = "expected '<count> <ordered digest> <set digest>' after '=>'", false;
  return true;
}

}  // namespace tessera::oracle
