// Comparing Tessera's tessellator with the D3D11 reference as Mesa's llvmpipe runs it.
//
// The oracle (shared/bench/tessref.cpp, built by tools/oracle/run_oracle.sh) reads cases in GL
// terms and writes, per case, every captured vertex's gl_TessCoord as exact hex floats. GL names
// map to D3D11 ones: equal_spacing = integer, GL `ccw` = D3D triangle_cw (positive (u,v) area),
// GL `cw` = triangle_ccw, point mode = point, isolines = line.
//
// Comparison is on float bit patterns. Primitives are compared in order and as a canonical set
// (each triangle rotated to start at its smallest vertex, winding kept; each segment sorted):
// llvmpipe's capture order is its own, the set is what must match.
#pragma once

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include "tessellator/tessellator.h"

namespace tessera::oracle {

struct Case {
  std::string line;  // the case line as given to the oracle
  ts::Partitioning partitioning = ts::Partitioning::integer;
  ts::OutputPrimitive output = ts::OutputPrimitive::triangle_cw;
  ts::FactorSet factors;
};

// Parses one oracle case line ("DOMAIN SPACING WINDING MODE O0 O1 O2 O3 I0 I1", GL names).
// Returns false with `error` set if the line is malformed.
bool parse_case_line(const std::string& line, Case& out, std::string& error);
// The oracle line for a case (inverse of parse_case_line).
// The GL spacing that runs a D3D11 partitioning: pow2 is integer to the tessellator (D3D11 §11.7.7.1;
// the rounding to powers of two is the hull shader's), so it maps to equal_spacing.
const char* gl_spacing(ts::Partitioning p);

std::string case_line(ts::Domain d, ts::Partitioning p, ts::OutputPrimitive o, const std::array<float, 6>& factors);

// One primitive's vertices as (u, v, w) float bit patterns; w = (1-u)-v for tri, else 0.
using Vertex = std::array<std::uint32_t, 3>;
using Primitive = std::vector<Vertex>;

struct Capture {
  Case c;
  std::vector<Primitive> primitives;  // in capture order
};

// Reads a tessref dump. Returns false with `error` ("line N: ...") on malformed input.
bool read_dump(std::istream& in, std::vector<Capture>& out, std::string& error);

// Tessera's primitives for a case, as the oracle would capture them.
std::vector<Primitive> tessera_primitives(const Case& c);

// Canonical digests: 64-bit FNV-1a over the primitives in order, and over the canonical sorted set.
struct Digest {
  std::size_t primitives = 0;
  std::uint64_t ordered = 0;
  std::uint64_t set = 0;
  friend bool operator==(const Digest&, const Digest&) = default;
};
Digest digest(const std::vector<Primitive>& prims);

struct Comparison {
  bool set_equal = false;
  bool order_equal = false;
  std::string detail;  // first difference, for a human
};
Comparison compare(const std::vector<Primitive>& reference, const std::vector<Primitive>& ours);

// Golden digests file: one line per case, "<case line> => <n> <ordered hex> <set hex>".
std::string golden_line(const Case& c, const Digest& d);
bool parse_golden_line(const std::string& line, Case& c, Digest& d, std::string& error);

}  // namespace tessera::oracle
