// Synthetic control cages for scaling measurements (memory, speed) where a real asset of the wanted
// size does not exist: cages built from a formula, with UVs, closed and all-quad.
//
// Contract: the result passes validate_cage (topology.h); sizes outside the stated ranges throw
// std::invalid_argument.
#pragma once

#include "shaders_cpp/cage/cage.h"

namespace tessera {

// A torus of `around` x `across` quads (each 3..4096): major radius `major`, tube radius `minor`
// (0 < minor < major), counter-clockwise seen from outside, every vertex of valence 4. UVs run
// u = i / around, v = j / across over [0, 1]^2, so the cage has one UV seam loop in each direction
// (around + across seam edges), as a real unwrapped asset has seams.
Cage torus_cage(int around, int across, float major, float minor);

// A sphere of radius `radius` whose two poles have valence `pole_valence` (3..2048): `across` (2..4096)
// bands of latitude; each band between the poles' rings has 2 * pole_valence quads, and at each pole
// pole_valence quads (pole, ring vertices 2k, 2k+1, 2k+2) close the surface, all-quad. The cage for
// measuring the ripples a scheme leaves around a high-valence vertex. UVs: u around, v from the south
// pole (0) to the north (1), the poles' corners at the middle of their quad's u span.
// `triangle_poles`: a latitude-longitude sphere instead, pole_valence vertices per latitude and a fan of
// pole_valence triangles at each pole (a polar configuration, polar_patch.h).
Cage sphere_cage(int pole_valence, int across, float radius, bool triangle_poles = false);

}  // namespace tessera
