// Collects a cage's patches as build_patches' constructions make them: each patch's stencil table
// (deduplicated by content: the talk's topology combinations), its IA patch, its summation order, and
// the control-point pre-pass's rows for a 1-ring larger than an IA patch holds.
//
// Contract
// - add() appends one patch to a group, in the order called: the constructions call it in face order,
//   so each group's patches keep face order.
// - Tables are interned by their weights, row count and ring size: equal tables share an index. Weights
//   below kResidualWeight are zero, so that a table depends on its faces' structure, not on the order of
//   their vertices' numbers.
// - A patch's `order` lists its IA patch's positions by ascending cage vertex index (stencil.h: the
//   hull shader sums in that order, so shared points come out bit-identical).
// - reserve() holds a patch's place in face order for a patch whose table is already known (a face of
//   a topology combination built before); place() fills it later, from any thread (one slot per call,
//   nothing else written), and add_into() fills it with a full construction instead (one thread).
// - finish() once, after the last add() and every reserved slot filled: it numbers the tables in the
//   order the patches first use them and fills both groups' index buffers, each patch's ring padded
//   with its first vertex to the group's largest ring.
// - A stencil reaching outside the ring, or a ring over 32 points that cannot be precomputed, is a
//   construction's bug: a CageError naming the face (bad data never gets here).
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/subdiv/stencil.h"
#include "shaders_cpp/subdiv/subd_patches.h"

namespace tessera::subdiv {

// Table weights below this are taken as zero (round-off where a mask's terms cancel); the schemes'
// smallest true weights (valence 360's Gregory masks, semi-sharp blends) are above 1e-9.
inline constexpr double kResidualWeight = 1e-12;

class PatchAssembler {
 public:
  PatchAssembler(const Cage& cage, SubdPatches& out) : cage_(cage), out_(out) {}

  // Adds a patch whose control points are `stencils` over the gathered ring. A ring larger than an IA
  // patch (only the stencil schemes' rings can be) makes a precomputed patch: its IA patch is the face's
  // `corners` (the ring's first entries) and its rows go to the pre-pass. Returns the patch, for the
  // construction's crease masks.
  SubdPatch& add(PatchGroup& group, int face, int sub, PatchKind kind, const std::vector<int>& ring,
                 const std::vector<Stencil>& stencils, const std::array<EdgeFactorKey, 4>& edges, int rotation = 0,
                 int corners = 0);

  // A place for one patch in `group`, after those added so far; returns its slot for place() or
  // add_into().
  int reserve(PatchGroup& group);
  // Storage for `count` slots (add() or reserve() calls) ahead: a hint, no slot is made.
  void reserve_slots(std::size_t count) {
    rings_.reserve(count), groups_.reserve(count), index_.reserve(count);
  }
  // Slot `slot` becomes the patch of `face` over `ring` with stencil table `table` (an index returned
  // in an earlier patch's `table`): what add() makes of the same ring and of stencils whose table that
  // is, without building them. Safe to call concurrently for different slots.
  void place(int slot, int face, PatchKind kind, std::vector<int> ring, int table,
             const std::array<EdgeFactorKey, 4>& edges, int rotation);
  // The next add() fills slot `slot` instead of appending.
  void add_into(int slot) { into_ = slot; }

  // Fills each group's index buffer once every patch is known (the control point count is the
  // group's largest ring).
  void finish();

 private:
  int intern(StencilTable&& table);

  const Cage& cage_;
  SubdPatches& out_;
  std::map<std::string, int> interned_;
  std::vector<std::vector<int>> rings_;  // per slot: its IA patch
  std::vector<PatchGroup*> groups_;      // per slot: its group
  std::vector<std::size_t> index_;       // per slot: its patch's index in its group
  int into_ = -1;                        // add_into()'s slot, until the next add()
};

}  // namespace tessera::subdiv
