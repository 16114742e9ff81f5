// Joining two rows of points with triangles (internal to the tessellator).
//
// Every ring side is stitched as an "outside" row (the ring farther out) and an "inside" row. A
// Row maps a position along the row to a point index. Rows are usually consecutive points, but
// the last side of a ring wraps back to the ring's first point, and the degenerate centre row of
// an even-parity quad is walked backwards on its return trip; the reference fakes these with
// index-patching state, here each Row says it directly.
#pragma once

#include <cstdint>
#include <vector>

#include "tessellator/tessellator.h"

namespace tessera::ts::detail {

struct Row {
  int base = 0;
  int step = 1;      // +1 forward, -1 backward through the point array
  int wrap_at = -1;  // this position is replaced by wrap_to (the ring's first point), -1: none
  int wrap_to = 0;
  int operator()(int position) const { return position == wrap_at ? wrap_to : base + step * position; }
};

// Appends triangles given clockwise (positive (u,v) area); flips to CCW when asked.
class TriangleWriter {
 public:
  TriangleWriter(std::vector<std::uint32_t>& indices, bool counter_clockwise)
      : indices_(indices), ccw_(counter_clockwise) {}
  void clockwise(int a, int b, int c) {
    indices_.push_back(static_cast<std::uint32_t>(a));
    indices_.push_back(static_cast<std::uint32_t>(ccw_ ? c : b));
    indices_.push_back(static_cast<std::uint32_t>(ccw_ ? b : c));
  }

 private:
  std::vector<std::uint32_t>& indices_;
  bool ccw_;
};

enum class Diagonals { inside_to_outside, inside_to_outside_except_middle, mirrored };

// Two rows whose point counts differ by 0 (a strip) or by 2 (a trapezoid: the outside row has one
// extra point at each end). `inside_points` is the inside row's point count.
void stitch_regular(TriangleWriter& out, bool trapezoid, Diagonals diagonals, int inside_points, Row inside,
                    Row outside);

// Two rows with arbitrary factors and parities (an outer edge and the first inner ring): points
// advance in ruler-function split order from both ends towards the middle.
void stitch_transition(TriangleWriter& out, Row inside, int inside_half_points, Parity inside_parity, Row outside,
                       int outside_half_points, Parity outside_parity);

}  // namespace tessera::ts::detail
