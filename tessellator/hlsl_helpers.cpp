#include "tessellator/hlsl_helpers.h"

#include <bit>
#include <cmath>

#include "tessellator/d3d_float.h"

namespace tessera::ts::hlsl {
namespace {

constexpr float kThree = 3.0f;

bool is_integer_like(Partitioning p) { return p == Partitioning::integer || p == Partitioning::pow2; }
bool is_even(float x) { return (static_cast<int>(x) & 1) == 0; }

// Parity of a rounded inside factor; 1 counts as even (it tessellates as 2).
Parity inside_parity(float rounded, Partitioning p) {
  if (is_integer_like(p)) return (is_even(rounded) || rounded == 1.0f) ? Parity::even : Parity::odd;
  return p == Partitioning::fractional_odd ? Parity::odd : Parity::even;
}

float reduce(Reduction r, float a, float b) {
  switch (r) {
    case Reduction::min: return d3d_fmin(a, b);
    case Reduction::max: return d3d_fmax(a, b);
    case Reduction::average: break;
  }
  return (a + b) / 2;
}

// Anti-popping replacement for an odd inside factor below 3 (scale ignored).
float anti_pop(Reduction r, float reduced_max, float reduced_average) {
  return d3d_fmin(kThree, r == Reduction::max ? reduced_max : reduced_average);
}

}  // namespace

std::string_view to_string(Reduction r) {
  switch (r) {
    case Reduction::min: return "min";
    case Reduction::max: return "max";
    case Reduction::average: return "average";
  }
  return "?";
}

std::optional<Reduction> parse_reduction(std::string_view s) {
  for (Reduction r : {Reduction::min, Reduction::max, Reduction::average})
    if (s == to_string(r)) return r;
  if (s == "avg") return Reduction::average;
  return std::nullopt;
}

float cleanup_edge_factor(float x) { return (d3d_isnan(x) || x < 1.0f) ? 1.0f : x; }

float clamp_scale(float x) {
  if (d3d_isnan(x) || x < 0.0f) return 0.0f;
  return x > 1.0f ? 1.0f : x;
}

float round_factor(float x, Partitioning p) {
  if (p == Partitioning::pow2) {
    // Any mantissa bit set: bump the exponent and clear the mantissa (the next power of two).
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
    if (bits & 0x007FFFFFu) return std::bit_cast<float>((bits & 0x7F800000u) + 0x00800000u);
    return x;
  }
  if (p == Partitioning::integer) return std::ceil(x);
  return x;
}

float clamp_factor(float x, Partitioning p) {
  switch (p) {
    case Partitioning::fractional_odd: return d3d_fmin(kMaxOddTessFactor, d3d_fmax(x, kMinOddTessFactor));
    case Partitioning::fractional_even: return d3d_fmin(kMaxEvenTessFactor, d3d_fmax(x, kMinEvenTessFactor));
    case Partitioning::integer:
    case Partitioning::pow2: break;
  }
  return d3d_fmin(kMaxEvenTessFactor, d3d_fmax(x, kMinOddTessFactor));
}

QuadFactors process_quad(Partitioning p, Reduction r, QuadReductionAxis axis, const QuadFactors& in,
                         QuadFactors* unrounded) {
  if (!(in.Ueq0 > 0) || !(in.Veq0 > 0) || !(in.Ueq1 > 0) || !(in.Veq1 > 0)) {
    if (unrounded) *unrounded = {in.Ueq0, in.Veq0, in.Ueq1, in.Veq1, 0, 0};
    return {0, 0, 0, 0, 0, 0};  // culled: the tessellator will cull on these
  }
  const float Ueq0 = cleanup_edge_factor(in.Ueq0), Veq0 = cleanup_edge_factor(in.Veq0);
  const float Ueq1 = cleanup_edge_factor(in.Ueq1), Veq1 = cleanup_edge_factor(in.Veq1);
  QuadFactors raw{Ueq0, Veq0, Ueq1, Veq1, 0, 0};
  QuadFactors out{};
  auto edge = [&](float x) { return is_integer_like(p) ? clamp_factor(round_factor(x, p), p) : clamp_factor(x, p); };
  out.Ueq0 = edge(Ueq0), out.Veq0 = edge(Veq0), out.Ueq1 = edge(Ueq1), out.Veq1 = edge(Veq1);

  float inside[2];
  Parity parity[2];
  auto finish = [&](int a, float value) {  // clamp, record unrounded, round, parity
    value = clamp_factor(value, p);
    (a == 0 ? raw.insideU : raw.insideV) = value;
    value = is_integer_like(p) ? round_factor(value, p) : value;
    parity[a] = inside_parity(value, p);
    inside[a] = value;
  };
  auto finish_anti_pop = [&](int a, float value) {
    value = clamp_factor(value, p);
    (a == 0 ? raw.insideU : raw.insideV) = value;
    if (p == Partitioning::integer) {  // pow2 never gets here: its rounded factors are even
      value = round_factor(value, p);
      parity[a] = is_even(value) ? Parity::even : Parity::odd;
    }
    inside[a] = value;
  };

  if (axis == QuadReductionAxis::one_axis) {
    float reduced;
    switch (r) {
      case Reduction::min: reduced = d3d_fmin(d3d_fmin(Veq0, Veq1), d3d_fmin(Ueq0, Ueq1)); break;
      case Reduction::max: reduced = d3d_fmax(d3d_fmax(Veq0, Veq1), d3d_fmax(Ueq0, Ueq1)); break;
      default: reduced = (Veq0 + Veq1 + Ueq0 + Ueq1) / 4; break;
    }
    finish(0, reduced * clamp_scale(in.insideU));
    if (parity[0] == Parity::odd && inside[0] < kThree)
      finish_anti_pop(
          0, anti_pop(r, d3d_fmax(d3d_fmax(Veq0, Veq1), d3d_fmax(Ueq0, Ueq1)), (Veq0 + Veq1 + Ueq0 + Ueq1) / 4));
    inside[1] = inside[0];
    raw.insideV = raw.insideU;
  } else {
    finish(0, reduce(r, Veq0, Veq1) * clamp_scale(in.insideU));
    finish(1, reduce(r, Ueq0, Ueq1) * clamp_scale(in.insideV));
    if (parity[0] == Parity::odd && inside[0] < kThree)
      finish_anti_pop(0, anti_pop(r, d3d_fmax(Veq0, Veq1), (Veq0 + Veq1) / 2));
    if (parity[1] == Parity::odd && inside[1] < kThree)
      finish_anti_pop(1, anti_pop(r, d3d_fmax(Ueq0, Ueq1), (Ueq0 + Ueq1) / 2));
    // The picture frame must come in on all sides as far as the side with the smaller factor.
    for (int a = 0; a < 2; ++a) {
      const int other = (a + 1) & 1;
      if (parity[a] == Parity::odd && inside[a] < kThree && inside[a] < inside[other]) {
        inside[a] = d3d_fmin(inside[other], kThree);
        (a == 0 ? raw.insideU : raw.insideV) = inside[a];
      }
    }
  }
  out.insideU = inside[0];
  out.insideV = inside[1];
  if (unrounded) *unrounded = raw;
  return out;
}

TriFactors process_tri(Partitioning p, Reduction r, const TriFactors& in, TriFactors* unrounded) {
  if (!(in.Ueq0 > 0) || !(in.Veq0 > 0) || !(in.Weq0 > 0)) {
    if (unrounded) *unrounded = {in.Ueq0, in.Veq0, in.Weq0, 0};
    return {0, 0, 0, 0};
  }
  const float Ueq0 = cleanup_edge_factor(in.Ueq0), Veq0 = cleanup_edge_factor(in.Veq0),
              Weq0 = cleanup_edge_factor(in.Weq0);
  TriFactors raw{Ueq0, Veq0, Weq0, 0};
  auto edge = [&](float x) { return is_integer_like(p) ? clamp_factor(round_factor(x, p), p) : clamp_factor(x, p); };
  TriFactors out{edge(Ueq0), edge(Veq0), edge(Weq0), 0};

  float inside;
  switch (r) {
    case Reduction::min: inside = d3d_fmin(d3d_fmin(Ueq0, Veq0), Weq0); break;
    case Reduction::max: inside = d3d_fmax(d3d_fmax(Ueq0, Veq0), Weq0); break;
    default: inside = (Ueq0 + Veq0 + Weq0) / 3; break;
  }
  inside = clamp_factor(inside * d3d_fmin(1.0f, clamp_scale(in.inside)), p);
  raw.inside = inside;
  if (is_integer_like(p)) inside = round_factor(inside, p);
  const Parity parity = inside_parity(inside, p);
  if (parity == Parity::odd && inside < kThree) {
    inside = clamp_factor(anti_pop(r, d3d_fmax(Ueq0, d3d_fmax(Veq0, Weq0)), (Ueq0 + Veq0 + Weq0) / 3), p);
    raw.inside = inside;
    if (p == Partitioning::integer) inside = round_factor(inside, p);
  }
  out.inside = inside;
  if (unrounded) *unrounded = raw;
  return out;
}

IsolineFactors process_isoline(Partitioning p, const IsolineFactors& in, IsolineFactors* unrounded) {
  if (!(in.density > 0) || !(in.detail > 0)) {
    if (unrounded) *unrounded = in;
    return {0, 0};
  }
  float detail = clamp_factor(cleanup_edge_factor(in.detail), p);
  float density = clamp_factor(cleanup_edge_factor(in.density), Partitioning::integer);
  if (unrounded) *unrounded = {density, detail};
  if (is_integer_like(p)) detail = round_factor(detail, p);
  density = round_factor(density, Partitioning::integer);
  return {density, detail};
}

}  // namespace tessera::ts::hlsl
