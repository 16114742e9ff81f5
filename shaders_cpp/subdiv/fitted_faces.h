// The faces the per-face schemes (gregory, bspline, acc) fit to the exact limit (limit_fit.h), and the
// points they share: a fitted face is a triangle or quad with a tagged corner (fits_limit); its corner
// points are the limit's, its edge points and face points least-squares fits.
//
// An edge is fitted when a tag or the boundary is at one of its ends. With neither, its limit curve is
// the smooth one (a tag changes only vertex points, and the curve reads the edge and face points
// around its ends), which the masks' edge points follow with face points made for them; at the
// boundary the masks are further from the limit than the fit (docs/schemes.md has the measurements).
// The face points of every triangle or quad beside a fitted edge are fitted too, so that they match
// that edge rather than the masks' one.
//
// Contract
// - Shared rows are computed once and read by every face that uses them, so both sides of an edge
//   and every face at a vertex get the same bits: a tagged vertex's corner from the lowest-index fitted
//   face at it, a fitted edge's points from the lowest-index fitted face on it.
// - A fitted row is kept only where it stays within the two vertex neighbourhoods of its edge (the
//   rings of both faces reach them), dropping terms below kNegligibleFitWeight; otherwise the masks'
//   rows stand.
// - The caches make a FittedFaces the state of one build_patches call: not shared between threads.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/subdiv/limit_fit.h"
#include "shaders_cpp/subdiv/subd_patches.h"

namespace tessera::subdiv {

// A fitted stencil's term outside its edge's neighbourhood is Bfr's approximation of an irregular
// surface at round-off; above this weight it is not, and the fit is not used.
inline constexpr double kNegligibleFitWeight = 1e-9;

class FittedFaces {
 public:
  // `refit`: untagged faces fitted too (build_patches), every edge of theirs with them.
  FittedFaces(const Cage& cage, const Topology& t, Scheme scheme, std::span<const char> refit = {});

  // Whether any face is fitted: without one, every call below leaves the rows as they are.
  bool any() const { return limit_ != nullptr; }
  int refit_count() const { return refit_count_; }
  const LimitStencils& limit() const { return *limit_; }
  bool fitted(int face) const { return fitted_[std::size_t(face)] != 0; }
  // The fitted faces and the triangles and quads beside a fitted edge.
  bool fits_face_points(int face) const { return fit_points_[std::size_t(face)] != 0; }
  bool is_fitted_edge(std::int64_t key) const { return edge_owner_.contains(key); }

  // Row p_row becomes the limit at tagged vertex v, where a fitted face has it.
  void fit_corner(std::vector<Stencil>& rows, int v, std::size_t p_row);
  // Replaces the edge points of a patch edge (vertices va -> vb, P rows pa, pb; E rows ea beside va, eb
  // beside vb) by the fitted ones when the edge is fitted.
  void fit_edge(std::vector<Stencil>& rows, int va, int vb, std::size_t pa, std::size_t pb, std::size_t ea,
                std::size_t eb);
  // The limit's derivative into fitted face g across its edge e (neighbour_cross_rows), or nullopt.
  std::optional<std::array<Stencil, 4>> inward_derivative(int g, int e) const;

 private:
  struct FittedEdge {
    bool ok = false;
    int a = -1;  // near_a lies beside vertex a
    EdgePoints points;
  };

  const Cage& cage_;
  const Topology& t_;
  std::unique_ptr<LimitStencils> limit_;
  std::vector<char> fitted_, fit_points_;
  int refit_count_ = 0;
  std::map<std::int64_t, int> edge_owner_;  // edge key -> the lowest fitted face on it
  std::map<int, std::optional<Stencil>> corners_;
  std::map<std::int64_t, FittedEdge> edges_;
};

}  // namespace tessera::subdiv
