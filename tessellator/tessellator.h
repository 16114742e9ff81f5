// Tessera's fixed-function tessellator: the Direct3D 11 tessellator, bit for bit.
//
// Contract
// - Given the same domain, partitioning, output primitive and factors, this produces the same domain
//   points (as float32 bit patterns), the same primitives and the same order as Microsoft's D3D11
//   reference tessellator (CHWTessellator, "D3D11 Fixed Function Tessellator Reference, May 7 2012").
// - Pure and reentrant: no state survives a call, nothing is global and mutable. Many threads may
//   tessellate at once; each passes its own Pattern, whose storage is reused between calls.
// - Factors may be any float: NaN, +-Inf, -0, denormals, huge values. Edge factors that are <= 0,
//   -0 or NaN cull the patch (Pattern::culled, no points); everything else is clamped as D3D11 does.
// - Three phases, as the reference has them: process_*_factors() turns raw floats into
//   ProcessedFactors (fixed point, parities, culling, the minimal case); generate() turns those into
//   points and indices. A pattern is a pure function of ProcessedFactors, which is hashable, so a
//   caller can cache patterns (two patches whose processed factors are equal tessellate the same).
//
// Conventions (D3D11's, in the reference's names)
// - Quad edges in SV_TessFactor order: Ueq0 (the edge where u == 0), Veq0, Ueq1, Veq1; inside
//   factors U then V. Tri edges: Ueq0, Veq0, Weq0; one inside factor. Isolines: density (number
//   of lines, always integer-partitioned) then detail (segments along each line).
// - Points are SV_DomainLocation (u, v); for triangles w = (1 - u) - v, which is exact.
// - triangle_cw gives positive signed area in (u, v); triangle_ccw swaps the 2nd and 3rd index.
// - Output point lists every point once (index i = point i); output line on isolines gives the
//   segments of each line; on tri/quad domains it links the points in generation order, as the
//   reference does (a debugging aid, not a wireframe).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "tessellator/fixed_point.h"

namespace tessera::ts {

enum class Domain : std::uint8_t { quad, tri, isoline };
enum class Partitioning : std::uint8_t { integer, pow2, fractional_odd, fractional_even };
enum class OutputPrimitive : std::uint8_t { point, line, triangle_cw, triangle_ccw };
enum class Parity : std::uint8_t { even, odd };

std::string_view to_string(Domain d);
std::string_view to_string(Partitioning p);
std::string_view to_string(OutputPrimitive o);
std::optional<Domain> parse_domain(std::string_view s);
std::optional<Partitioning> parse_partitioning(std::string_view s);
std::optional<OutputPrimitive> parse_output_primitive(std::string_view s);

// Clamp ranges (D3D11.3 §11.7.10).
inline constexpr float kMinOddTessFactor = 1.0f;
inline constexpr float kMaxOddTessFactor = 63.0f;
inline constexpr float kMinEvenTessFactor = 2.0f;
inline constexpr float kMaxEvenTessFactor = 64.0f;
inline constexpr float kMinIsolineDensity = 1.0f;
inline constexpr float kMaxIsolineDensity = 64.0f;
// Upper bounds on one pattern's size, for callers that size buffers up front.
inline constexpr std::size_t kMaxPointCount = 65 * 65;
inline constexpr std::size_t kMaxIndexCount = 64 * 64 * 2 * 3;

// Raw factors as a hull shader's patch-constant function writes them.
struct QuadFactors {
  float Ueq0, Veq0, Ueq1, Veq1;
  float insideU, insideV;
};
struct TriFactors {
  float Ueq0, Veq0, Weq0;
  float inside;
};
struct IsolineFactors {
  float density;  // SV_TessFactor[0]: how many lines (v direction)
  float detail;   // SV_TessFactor[1]: segments along each line (u direction)
};

// What one factor becomes after processing: everything point placement along that edge needs.
// (The reference's TESS_FACTOR_CONTEXT plus the parity that its hidden m_parity used to carry.)
struct EdgeContext {
  Fxp factor = 0;  // clamped, rounded (integer) factor in 16.16
  Parity parity = Parity::even;
  int num_points = 0;          // points along the edge, both ends included
  int num_half_points = 0;     // points on one half, the midpoint excluded
  int split_point = 0;         // the point that splits off its parent as the factor grows (ruler function)
  Fxp half_fraction = 0;       // fractional part of factor/2: how far the split point has moved
  Fxp inv_floor_segments = 0;  // reciprocal-table entries for the floor and ceil segment counts
  Fxp inv_ceil_segments = 0;
  friend bool operator==(const EdgeContext&, const EdgeContext&) = default;
};

// Result of factor processing for one patch. Equal values tessellate to identical patterns.
struct ProcessedFactors {
  Domain domain = Domain::quad;
  bool culled = false;
  bool minimal = false;  // every factor is exactly 1 (integer/odd): the reference's shortcut
  std::array<EdgeContext, 4>
      outside{};  // quad: Ueq0 Veq0 Ueq1 Veq1; tri: Ueq0 Veq0 Weq0; isoline: [0] density, [1] detail
  std::array<EdgeContext, 2> inside{};  // quad: U V; tri: [0]
  friend bool operator==(const ProcessedFactors&, const ProcessedFactors&) = default;
};

ProcessedFactors process_quad_factors(Partitioning partitioning, const QuadFactors& f);
ProcessedFactors process_tri_factors(Partitioning partitioning, const TriFactors& f);
ProcessedFactors process_isoline_factors(Partitioning partitioning, const IsolineFactors& f);

// A 64-bit hash of processed factors, for pattern caches keyed on (ProcessedFactors, OutputPrimitive).
std::uint64_t hash(const ProcessedFactors& p, OutputPrimitive output);

struct DomainPoint {
  float u, v;
  friend bool operator==(const DomainPoint&, const DomainPoint&) = default;
};

// The tessellator's output. `indices` holds vertices_per_primitive() indices per primitive.
struct Pattern {
  bool culled = false;
  OutputPrimitive output = OutputPrimitive::triangle_cw;
  Domain domain = Domain::quad;
  std::vector<DomainPoint> points;
  std::vector<std::uint32_t> indices;

  int vertices_per_primitive() const;
  std::size_t primitive_count() const { return indices.size() / std::size_t(vertices_per_primitive()); }
  void clear();
};

// Generates the pattern for already-processed factors into `out` (its storage is reused).
void generate(const ProcessedFactors& processed, OutputPrimitive output, Pattern& out);

// The number of primitives generate(processed, output, out) makes (out.primitive_count()), computed
// from the factors without generating anything; 0 for a culled patch.
std::size_t primitive_count(const ProcessedFactors& processed, OutputPrimitive output);

// process + generate in one call.
void tessellate_quad(Partitioning partitioning, OutputPrimitive output, const QuadFactors& f, Pattern& out);
void tessellate_tri(Partitioning partitioning, OutputPrimitive output, const TriFactors& f, Pattern& out);
void tessellate_isoline(Partitioning partitioning, OutputPrimitive output, const IsolineFactors& f, Pattern& out);

// Factors as a flat list in SV_TessFactor / SV_InsideTessFactor order, for tools and tests:
// quad {Ueq0, Veq0, Ueq1, Veq1, insideU, insideV}, tri {Ueq0, Veq0, Weq0, inside}, isoline {density, detail}.
struct FactorSet {
  Domain domain = Domain::quad;
  std::array<float, 6> values{};
};
ProcessedFactors process_factors(Partitioning partitioning, const FactorSet& f);
void tessellate(Partitioning partitioning, OutputPrimitive output, const FactorSet& f, Pattern& out);

// How many outer and inside factors a domain takes.
int outer_factor_count(Domain d);
int inside_factor_count(Domain d);

}  // namespace tessera::ts
