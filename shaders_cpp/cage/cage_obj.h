// Reading a control cage from Wavefront OBJ text with OpenSubdiv's tag lines.
//
// Accepted:
//   v x y z [w]        a position (w, a rational weight, is ignored with a warning unless 1;
//                      `v x y z r g b` vertex colours are ignored)
//   vt u [v [w]]       a texture coordinate (w ignored)
//   vn ...             ignored (the limit surface has its own normals)
//   f a b c ...        a face of 3 or more corners, each `v`, `v/vt`, `v/vt/vn` or `v//vn`; indices are
//                      1-based, negative ones count back from the last element read so far
//   t name i/f/s ints floats strings
//                      an OpenSubdiv tag (their regression shapes' format). Vertex and face indices in
//                      tags are 0-based, as OpenSubdiv writes them:
//     crease   pairs of vertex indices, and one sharpness for all pairs or one per pair
//     corner   vertex indices, and one sharpness for all or one per vertex
//     hole     face indices
//     interpolateboundary 0|1|2 (none | edge_and_corner | edge_only), creasemethod normal|chaikin,
//     smoothtriangles catmark|smooth, facevaryinginterpolateboundary 0..5,
//     facevaryingpropagatecorners 0|1
//   g o s mtllib usemtl l p, comments (#...), blank lines, CRLF line ends, and `\` at the end of a line
//   (continues the statement on the next line).
// Unknown tags (OpenSubdiv's hierarchical edits `vertexedit`, `edgeedit`, `faceedit`, which Far 3 does not
// support) and unknown statements are ignored with a line in Cage::warnings.
//
// Errors throw CageError with one line "NAME:LINE: what is wrong", e.g. "frog.obj:12: face 7 has vertex
// index 1400, but the cage has 1308 vertices". Checked: malformed or non-finite numbers, index 0 or out of
// range (faces, UVs, tag vertices and faces), faces with fewer than 3 corners, faces with texture
// coordinates mixed with faces without, tags with the wrong number of arguments, an empty cage (no faces).
// Non-manifold places (edges of three or more faces or used twice the same way, faces repeating a vertex,
// vertices of several fans) are split as OpenSubdiv draws them (non_manifold.h), so the cage returned is
// manifold; what is left (such as a face naming one vertex twice within one fan) Topology refuses.
//
// Cost: one pass over the text, O(size of the file), in parallel where the text allows (ObjParse).
#pragma once

#include <string>
#include <string_view>

#include "shaders_cpp/cage/cage.h"

namespace tessera {

// Reads the file at `path`; Cage::name is `path`. Throws CageError (also when the file cannot be read).
Cage load_obj_cage(const std::string& path);

// How a text is parsed: in chunks of about a megabyte, in parallel on the calling task arena's threads,
// where it holds only positions, texture coordinates, faces with absolute indices and ignored
// statements (else, and for a text under two megabytes, whole); or whole, on one thread (for tests:
// the same cage, the same errors and warnings).
enum class ObjParse : unsigned char { chunks, serial };

// Parses OBJ text; `name` names the source in messages and becomes Cage::name.
Cage parse_obj_cage(std::string_view text, std::string name, ObjParse how = ObjParse::chunks);

// The OBJ text of a cage that parse_obj_cage reads back to the same positions (bit for bit: shortest
// round-trip decimals), UVs, faces and tags (creases, corners, holes, boundary interpolation, crease method, smooth
// triangles, face-varying interpolation);
// warnings and the name are not written.
std::string format_obj_cage(const Cage& cage);

}  // namespace tessera
