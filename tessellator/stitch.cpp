#include "tessellator/stitch.h"

#include <array>

namespace tessera::ts::detail {

void stitch_regular(TriangleWriter& out, bool trapezoid, Diagonals diagonals, int inside_points, Row inside,
                    Row outside) {
  int in = 0, o = 0;
  // Each step emits the quad between inside positions in, in+1 and outside positions o, o+1.
  auto quad_outside_first = [&] {  // diagonal from the outside point forward to the inside point
    out.clockwise(outside(o), outside(o + 1), inside(in));
    out.clockwise(inside(in), outside(o + 1), inside(in + 1));
  };
  auto quad_inside_first = [&] {  // diagonal from the inside point forward to the outside point
    out.clockwise(inside(in), outside(o), outside(o + 1));
    out.clockwise(inside(in), outside(o + 1), inside(in + 1));
  };
  auto quad_mirrored_first_half = [&] {
    out.clockwise(outside(o), inside(in + 1), inside(in));
    out.clockwise(outside(o), outside(o + 1), inside(in + 1));
  };
  if (trapezoid) {
    out.clockwise(outside(o), outside(o + 1), inside(in));
    ++o;
  }
  const int quads = inside_points - 1;
  switch (diagonals) {
    case Diagonals::inside_to_outside:
      for (int p = 0; p < quads; ++p, ++in, ++o) quad_inside_first();
      break;
    case Diagonals::inside_to_outside_except_middle: {
      // Odd rows only: the middle quad's diagonal is turned so the centre is symmetric.
      const int first_half = inside_points / 2 - 1;
      for (int p = 0; p < first_half; ++p, ++in, ++o) quad_outside_first();
      quad_mirrored_first_half();
      ++in, ++o;
      for (int p = first_half + 1; p < quads; ++p, ++in, ++o) quad_outside_first();
      break;
    }
    case Diagonals::mirrored: {
      // Diagonals point away from the middle on both halves: from the outside corner inwards first.
      const int half = inside_points / 2;
      int p = 0;
      for (; p < half; ++p, ++in, ++o) quad_mirrored_first_half();
      for (; p < quads; ++p, ++in, ++o) quad_inside_first();
      break;
    }
  }
  if (trapezoid) out.clockwise(outside(o), outside(o + 1), inside(in));
}

namespace {

// Where the i-th point to appear on a half-edge ends up when the half-edge is fully tessellated
// (32 segments), in ruler-function split order. A row advances past table entry i once its own
// half-edge has more points than that position.
constexpr std::array<int, 33> kFinalPointPosition = {0, 32, 16, 8,  17, 4,  18, 9,  19, 2,  20, 10, 21, 5,  22, 11, 23,
                                                     1, 24, 12, 25, 6,  26, 13, 27, 3,  28, 14, 29, 7,  30, 15, 31};

}  // namespace

void stitch_transition(TriangleWriter& out, Row inside, int inside_half_points, Parity inside_parity, Row outside,
                       int outside_half_points, Parity outside_parity) {
  // An odd row's middle segment is stitched separately below; leave it out of the halves.
  if (inside_parity == Parity::odd) inside_half_points -= 1;
  if (outside_parity == Parity::odd) outside_half_points -= 1;
  int in = 0, o = 0;
  auto advance_outside = [&] {
    out.clockwise(outside(o), outside(o + 1), inside(in));
    ++o;
  };
  auto advance_inside = [&] {
    out.clockwise(inside(in), outside(o), inside(in + 1));
    ++in;
  };

  // First half, from the row ends towards the middle. Entry 0 (the corner) only ever advances
  // the outside row.
  if (kFinalPointPosition[0] < outside_half_points) advance_outside();
  for (int i = 1; i <= 32; ++i) {
    if (kFinalPointPosition[i] < inside_half_points) advance_inside();
    if (kFinalPointPosition[i] < outside_half_points) advance_outside();
  }

  // The middle.
  if (inside_parity != outside_parity || inside_parity == Parity::odd) {
    if (inside_parity == outside_parity) {  // both odd: a quad
      out.clockwise(inside(in), outside(o), inside(in + 1));
      out.clockwise(inside(in + 1), outside(o), outside(o + 1));
      ++in, ++o;
    } else if (inside_parity == Parity::even) {  // the outside row has the middle segment
      out.clockwise(inside(in), outside(o), outside(o + 1));
      ++o;
    } else {  // the inside row has it
      out.clockwise(inside(in), outside(o), inside(in + 1));
      ++in;
    }
  }

  // Second half, mirrored: outside first, then inside, walking the table backwards.
  for (int i = 32; i >= 1; --i) {
    if (kFinalPointPosition[i] < outside_half_points) advance_outside();
    if (kFinalPointPosition[i] < inside_half_points) advance_inside();
  }
  if (kFinalPointPosition[0] < outside_half_points) advance_outside();
}

}  // namespace tessera::ts::detail
