// OBJ cage reader: one pass over logical lines (continuations joined), a whitespace tokenizer, and
// range checks deferred to the end for what may legally be written before it is defined (tags usually
// follow the faces they name; some exporters refer to vertices written later).
#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/cage/non_manifold.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include <span>

#include <tbb/parallel_for.h>

namespace tessera {
namespace {

// A statement: its tokens and the (1-based) line on which it starts.
struct Statement {
  std::vector<std::string_view> tokens;
  int line = 0;
};

class ObjParser {
 public:
  ObjParser(std::string_view text, std::string name) : text_(text) { cage_.name = std::move(name); }

  // A chunk of the text, its first line numbered `first_line`: it takes positions, texture coordinates
  // and faces with absolute indices only, and throws Unchunkable at anything else (a tag, a warning, a
  // relative index, a continued line), which the whole text's serial parse then handles.
  struct Unchunkable {};
  static ObjParser chunk(std::string_view text, std::string name, int first_line) {
    ObjParser p(text, std::move(name));
    p.chunk_ = true;
    p.first_line_ = first_line;
    p.parse();
    return p;
  }

  // Room for `more` chunks' elements after this one's.
  void reserve_for(std::span<const std::optional<ObjParser>> more) {
    std::size_t positions = cage_.positions.size(), uvs = cage_.uvs.size(), faces = cage_.face_sizes.size(),
                corners = cage_.face_vertices.size(), face_uvs = face_uvs_.size();
    for (const auto& c : more)
      if (c) {
        positions += c->cage_.positions.size(), uvs += c->cage_.uvs.size(), faces += c->cage_.face_sizes.size();
        corners += c->cage_.face_vertices.size(), face_uvs += c->face_uvs_.size();
      }
    cage_.positions.reserve(positions), cage_.uvs.reserve(uvs), cage_.face_offsets.reserve(faces);
    cage_.face_sizes.reserve(faces), cage_.face_vertices.reserve(corners), face_uvs_.reserve(face_uvs);
    face_lines_.reserve(faces);
  }

  // Appends a chunk's elements (the chunk that follows this text), its line numbers `lines` on (the
  // chunk was parsed as if its first line were line 1).
  void append(ObjParser&& c, int lines) {
    if (c.cage_.face_count() > 0) {
      if (cage_.face_count() > 0 && c.faces_have_uvs_ != faces_have_uvs_) throw Unchunkable{};
      if (cage_.face_count() == 0) faces_have_uvs_ = c.faces_have_uvs_;
    }
    const int offset = int(cage_.face_vertices.size());
    cage_.positions.insert(cage_.positions.end(), c.cage_.positions.begin(), c.cage_.positions.end());
    cage_.uvs.insert(cage_.uvs.end(), c.cage_.uvs.begin(), c.cage_.uvs.end());
    for (const int o : c.cage_.face_offsets) cage_.face_offsets.push_back(o + offset);
    cage_.face_sizes.insert(cage_.face_sizes.end(), c.cage_.face_sizes.begin(), c.cage_.face_sizes.end());
    cage_.face_vertices.insert(cage_.face_vertices.end(), c.cage_.face_vertices.begin(), c.cage_.face_vertices.end());
    face_uvs_.insert(face_uvs_.end(), c.face_uvs_.begin(), c.face_uvs_.end());
    for (const int l : c.face_lines_) face_lines_.push_back(l + lines);
  }

  Cage run() {
    parse();
    return finished();
  }
  // The range checks of the whole cage, after its last chunk.
  Cage finished() {
    chunk_ = false;
    finish();
    return std::move(cage_);
  }

 private:
  void parse() {
    Statement st;
    std::string joined;  // storage for a statement continued over several lines
    std::size_t pos = 0;
    int line = first_line_ - 1;
    while (pos < text_.size()) {
      // Gather one logical line: physical lines joined while they end with a backslash.
      const int first_line = line + 1;
      std::string_view logical;
      bool continued = false;
      joined.clear();
      while (pos < text_.size()) {
        std::size_t end = text_.find('\n', pos);
        if (end == std::string_view::npos) end = text_.size();
        std::string_view phys = text_.substr(pos, end - pos);
        pos = end + 1;
        ++line;
        if (!phys.empty() && phys.back() == '\r') phys.remove_suffix(1);
        const bool more = !phys.empty() && phys.back() == '\\';
        if (more && chunk_) throw Unchunkable{};
        if (more) phys.remove_suffix(1);
        if (!more && !continued) {
          logical = phys;
          break;
        }
        joined.append(phys);
        joined.push_back(' ');
        continued = true;
        if (!more) break;
      }
      if (continued) logical = joined;
      if (const auto hash = logical.find('#'); hash != std::string_view::npos) logical = logical.substr(0, hash);
      st.line = first_line;
      tokenize(logical, st.tokens);
      if (!st.tokens.empty()) statement(st);
    }
  }

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw CageError(cage_.name + ":" + std::to_string(line) + ": " + what);
  }
  void warn(int line, const std::string& what) {
    if (chunk_) throw Unchunkable{};
    cage_.warnings.push_back(cage_.name + ":" + std::to_string(line) + ": " + what);
  }

  static void tokenize(std::string_view s, std::vector<std::string_view>& out) {
    out.clear();
    std::size_t i = 0;
    while (i < s.size()) {
      while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r' || s[i] == '\f' || s[i] == '\v')) ++i;
      const std::size_t start = i;
      while (i < s.size() && !(s[i] == ' ' || s[i] == '\t' || s[i] == '\r' || s[i] == '\f' || s[i] == '\v')) ++i;
      if (i > start) out.push_back(s.substr(start, i - start));
    }
  }

  float number(std::string_view tok, int line, const char* what) const {
    std::string_view t = tok;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);  // from_chars does not take a '+'
    float x = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
    if (ec != std::errc() || p != t.data() + t.size() || t.empty())
      fail(line, std::string("bad number '") + std::string(tok) + "' in " + what);
    if (!std::isfinite(x)) fail(line, std::string("non-finite number '") + std::string(tok) + "' in " + what);
    return x;
  }

  int integer(std::string_view tok, int line, const char* what) const {
    std::string_view t = tok;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    int x = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
    if (ec != std::errc() || p != t.data() + t.size() || t.empty())
      fail(line, std::string("bad integer '") + std::string(tok) + "' in " + what);
    return x;
  }

  void statement(const Statement& st) {
    const std::string_view kw = st.tokens[0];
    if (kw == "v")
      vertex(st);
    else if (kw == "vt")
      texcoord(st);
    else if (kw == "f")
      face(st);
    else if (kw == "t" && chunk_)
      throw Unchunkable{};
    else if (kw == "t")
      tag(st);
    else if (kw == "vn" || kw == "g" || kw == "o" || kw == "s" || kw == "mtllib" || kw == "usemtl")
      return;
    else if (warned_.insert(std::string(kw)).second)
      warn(st.line, "statement '" + std::string(kw) + "' is not supported; ignored (and further ones)");
  }

  void vertex(const Statement& st) {
    const std::size_t n = st.tokens.size() - 1;
    if (n != 3 && n != 4 && n != 6) fail(st.line, "vertex needs 3 coordinates (x y z [w]), got " + std::to_string(n));
    const glm::vec3 p{number(st.tokens[1], st.line, "vertex"), number(st.tokens[2], st.line, "vertex"),
                      number(st.tokens[3], st.line, "vertex")};
    if (n == 4 && number(st.tokens[4], st.line, "vertex") != 1.0f && !warned_w_) {
      warned_w_ = true;
      warn(st.line, "vertex weight w is ignored");
    }
    cage_.positions.push_back(p);
  }

  void texcoord(const Statement& st) {
    const std::size_t n = st.tokens.size() - 1;
    if (n < 1 || n > 3) fail(st.line, "texture coordinate needs u [v [w]], got " + std::to_string(n) + " numbers");
    const float u = number(st.tokens[1], st.line, "texture coordinate");
    const float v = n >= 2 ? number(st.tokens[2], st.line, "texture coordinate") : 0.0f;
    if (n == 3) (void)number(st.tokens[3], st.line, "texture coordinate");
    cage_.uvs.push_back({u, v});
  }

  // Resolves an OBJ index (1-based, or negative = relative to `count` elements read so far) to 0-based.
  // Positive indices are range-checked in finish(), negative ones here.
  int resolve(std::string_view tok, int count, int line, int face, const char* what) const {
    const int i = integer(tok, line, what);
    if (i == 0) fail(line, "face " + std::to_string(face) + " has " + what + " index 0 (OBJ indices start at 1)");
    if (i > 0) return i - 1;
    if (chunk_) throw Unchunkable{};  // relative to what the chunks before have read
    const long long r = static_cast<long long>(count) + i;
    if (r < 0)
      fail(line, "face " + std::to_string(face) + " has relative " + what + " index " + std::to_string(i) +
                     ", but only " + std::to_string(count) + " were read so far");
    return static_cast<int>(r);
  }

  void face(const Statement& st) {
    const int f = cage_.face_count();
    const std::size_t n = st.tokens.size() - 1;
    if (n < 3)
      fail(st.line, "face " + std::to_string(f) + " has " + std::to_string(n) + " vertices; a face needs at least 3");
    bool any_uv = false, all_uv = true;
    cage_.face_offsets.push_back(static_cast<int>(cage_.face_vertices.size()));
    cage_.face_sizes.push_back(static_cast<int>(n));
    face_lines_.push_back(st.line);
    for (std::size_t k = 1; k <= n; ++k) {
      const std::string_view tok = st.tokens[k];
      const std::size_t s1 = tok.find('/');
      const std::string_view vs = tok.substr(0, s1);
      cage_.face_vertices.push_back(resolve(vs, cage_.vertex_count(), st.line, f, "vertex"));
      std::string_view ts;
      if (s1 != std::string_view::npos) {
        const std::size_t s2 = tok.find('/', s1 + 1);
        ts = tok.substr(s1 + 1, s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
        if (s2 != std::string_view::npos && tok.find('/', s2 + 1) != std::string_view::npos)
          fail(st.line, "face " + std::to_string(f) + " corner '" + std::string(tok) + "' has too many '/'");
      }
      if (!ts.empty()) {
        any_uv = true;
        face_uvs_.push_back(resolve(ts, static_cast<int>(cage_.uvs.size()), st.line, f, "texture coordinate"));
      } else {
        all_uv = false;
      }
    }
    if (any_uv && !all_uv)
      fail(st.line, "face " + std::to_string(f) + " gives texture coordinates for some corners but not all");
    if (f == 0)
      faces_have_uvs_ = any_uv;
    else if (any_uv != faces_have_uvs_)
      fail(st.line, "face " + std::to_string(f) + (any_uv ? " has" : " has no") +
                        " texture coordinates, but face 0 (line " + std::to_string(face_lines_[0]) + ")" +
                        (any_uv ? " has none" : " has them"));
  }

  // `t name nI/nF/nS ints floats strings`
  void tag(const Statement& st) {
    if (st.tokens.size() < 3) fail(st.line, "tag needs a name and counts nInts/nFloats/nStrings");
    const std::string name(st.tokens[1]);
    const std::string_view counts = st.tokens[2];
    const std::size_t a = counts.find('/'), b = a == std::string_view::npos ? a : counts.find('/', a + 1);
    if (b == std::string_view::npos)
      fail(st.line, "tag '" + name + "' has counts '" + std::string(counts) + "', expected nInts/nFloats/nStrings");
    const int ni = integer(counts.substr(0, a), st.line, "tag counts");
    const int nf = integer(counts.substr(a + 1, b - a - 1), st.line, "tag counts");
    const int ns = integer(counts.substr(b + 1), st.line, "tag counts");
    if (ni < 0 || nf < 0 || ns < 0) fail(st.line, "tag '" + name + "' has negative counts");
    const std::size_t want = 3 + std::size_t(ni) + std::size_t(nf) + std::size_t(ns);
    if (st.tokens.size() != want)
      fail(st.line, "tag '" + name + "' declares " + std::to_string(static_cast<long long>(ni) + nf + ns) +
                        " arguments but has " + std::to_string(st.tokens.size() - 3));
    std::vector<int> ints;
    std::vector<float> floats;
    for (int i = 0; i < ni; ++i) ints.push_back(integer(st.tokens[3 + std::size_t(i)], st.line, "tag"));
    for (int i = 0; i < nf; ++i) floats.push_back(number(st.tokens[3 + std::size_t(ni + i)], st.line, "tag"));
    const auto strings = std::vector<std::string_view>(st.tokens.begin() + 3 + ni + nf, st.tokens.end());
    auto expect = [&](int i, int f, int s) {
      if (ni != i || nf != f || ns != s)
        fail(st.line, "tag '" + name + "' takes " + std::to_string(i) + "/" + std::to_string(f) + "/" +
                          std::to_string(s) + " arguments, got " + std::string(counts));
    };
    auto sharpness = [&](float s) {
      if (s < 0)
        fail(st.line, "tag '" + name + "' has negative sharpness " + std::string(st.tokens[3 + std::size_t(ni)]));
      return s;
    };
    if (name == "crease") {
      if (ni < 2 || ni % 2 != 0 || ns != 0 || (nf != 1 && nf != ni / 2))
        fail(st.line, "crease takes pairs of vertices and one sharpness or one per pair, got " + std::string(counts));
      for (int p = 0; p < ni / 2; ++p) {
        cage_.tags.creases.push_back(
            {ints[std::size_t(2 * p)], ints[std::size_t(2 * p + 1)], sharpness(floats[nf == 1 ? 0 : std::size_t(p)])});
        crease_lines_.push_back(st.line);
      }
    } else if (name == "corner") {
      if (ni < 1 || ns != 0 || (nf != 1 && nf != ni))
        fail(st.line, "corner takes vertices and one sharpness or one per vertex, got " + std::string(counts));
      for (int p = 0; p < ni; ++p) {
        cage_.tags.corners.push_back({ints[std::size_t(p)], sharpness(floats[nf == 1 ? 0 : std::size_t(p)])});
        corner_lines_.push_back(st.line);
      }
    } else if (name == "hole") {
      if (nf != 0 || ns != 0) fail(st.line, "hole takes face indices only, got " + std::string(counts));
      for (int f : ints) {
        cage_.tags.holes.push_back(f);
        hole_lines_.push_back(st.line);
      }
    } else if (name == "interpolateboundary") {
      expect(1, 0, 0);
      static constexpr BoundaryInterpolation kModes[] = {
          BoundaryInterpolation::none, BoundaryInterpolation::edge_and_corner, BoundaryInterpolation::edge_only};
      if (ints[0] < 0 || ints[0] > 2)
        fail(st.line, "interpolateboundary must be 0, 1 or 2, got " + std::to_string(ints[0]));
      cage_.tags.boundary = kModes[ints[0]];
    } else if (name == "creasemethod") {
      expect(0, 0, 1);
      if (strings[0] == "normal")
        cage_.tags.crease_method = CreaseMethod::uniform;
      else if (strings[0] == "chaikin")
        cage_.tags.crease_method = CreaseMethod::chaikin;
      else
        fail(st.line, "creasemethod must be 'normal' or 'chaikin', got '" + std::string(strings[0]) + "'");
    } else if (name == "smoothtriangles") {
      expect(0, 0, 1);
      if (strings[0] == "smooth")
        cage_.tags.smooth_triangles = true;
      else if (strings[0] == "catmark")
        cage_.tags.smooth_triangles = false;
      else
        fail(st.line, "smoothtriangles must be 'catmark' or 'smooth', got '" + std::string(strings[0]) + "'");
    } else if (name == "facevaryinginterpolateboundary") {
      expect(1, 0, 0);
      if (ints[0] < 0 || ints[0] > 5)
        fail(st.line, "facevaryinginterpolateboundary must be 0..5, got " + std::to_string(ints[0]));
      cage_.tags.fvar_boundary = ints[0];
    } else if (name == "facevaryingpropagatecorners") {
      expect(1, 0, 0);
      cage_.tags.fvar_propagate_corners = ints[0] != 0;
    } else {
      warn(st.line, "tag '" + name + "' is not supported; ignored");
    }
  }

  // Range checks for what could be named before it was defined; the error names the line that named it.
  void finish() {
    const int nv = cage_.vertex_count(), nf = cage_.face_count();
    if (nf == 0) throw CageError(cage_.name + ": no faces" + (nv == 0 ? " (empty cage)" : ""));
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < cage_.face_sizes[std::size_t(f)]; ++k) {
        const int v = cage_.face_vertex(f, k);
        if (v >= nv)
          fail(face_lines_[std::size_t(f)], "face " + std::to_string(f) + " has vertex index " + std::to_string(v + 1) +
                                                ", but the cage has " + std::to_string(nv) + " vertices");
        if (faces_have_uvs_) {
          const int t = face_uvs_[std::size_t(cage_.face_offsets[std::size_t(f)] + k)];
          if (t >= int(cage_.uvs.size()))
            fail(face_lines_[std::size_t(f)], "face " + std::to_string(f) + " has texture coordinate index " +
                                                  std::to_string(t + 1) + ", but the cage has " +
                                                  std::to_string(cage_.uvs.size()) + " texture coordinates");
        }
      }
    if (faces_have_uvs_)
      cage_.face_uvs = std::move(face_uvs_);
    else
      cage_.uvs.clear();  // coordinates no face uses are of no use
    for (std::size_t i = 0; i < cage_.tags.creases.size(); ++i)
      for (int v : {cage_.tags.creases[i].v0, cage_.tags.creases[i].v1})
        if (v < 0 || v >= nv)
          fail(crease_lines_[i], "crease names vertex " + std::to_string(v) + ", but the cage has " +
                                     std::to_string(nv) + " vertices (0-based)");
    for (std::size_t i = 0; i < cage_.tags.corners.size(); ++i)
      if (const int v = cage_.tags.corners[i].vertex; v < 0 || v >= nv)
        fail(corner_lines_[i], "corner names vertex " + std::to_string(v) + ", but the cage has " + std::to_string(nv) +
                                   " vertices (0-based)");
    for (std::size_t i = 0; i < cage_.tags.holes.size(); ++i)
      if (const int f = cage_.tags.holes[i]; f < 0 || f >= nf)
        fail(hole_lines_[i],
             "hole names face " + std::to_string(f) + ", but the cage has " + std::to_string(nf) + " faces (0-based)");
    drop_creases_on_no_edge();
  }

  // A crease on two vertices that share no edge sharpens nothing: it is left out with a warning naming
  // its line, as OpenSubdiv's own tools do (OpenSubdiv's regression shapes hold such tags), so no
  // reader or library downstream ever sees it.
  void drop_creases_on_no_edge() {
    if (cage_.tags.creases.empty()) return;
    // The creases' vertex pairs that some face has as an edge (a scan of the faces, a lookup among the
    // creases' pairs: cheap however large the cage).
    std::set<std::pair<int, int>> wanted, edges;
    for (const Crease& c : cage_.tags.creases) wanted.insert({std::min(c.v0, c.v1), std::max(c.v0, c.v1)});
    for (int f = 0; f < cage_.face_count(); ++f) {
      const int n = cage_.face_sizes[std::size_t(f)];
      for (int k = 0; k < n; ++k) {
        const int a = cage_.face_vertex(f, k), b = cage_.face_vertex(f, (k + 1) % n);
        const std::pair<int, int> e{std::min(a, b), std::max(a, b)};
        if (wanted.count(e)) edges.insert(e);
      }
    }
    std::vector<Crease> kept;
    for (std::size_t i = 0; i < cage_.tags.creases.size(); ++i) {
      const Crease& c = cage_.tags.creases[i];
      if (c.v0 != c.v1 && edges.count({std::min(c.v0, c.v1), std::max(c.v0, c.v1)})) {
        kept.push_back(c);
        continue;
      }
      warn(crease_lines_[i], "crease " + std::to_string(c.v0) + " " + std::to_string(c.v1) +
                                 " names no edge of the cage (vertices from 0); left out");
    }
    cage_.tags.creases = std::move(kept);
  }

  std::string_view text_;
  Cage cage_;
  std::vector<int> face_uvs_;
  std::vector<int> face_lines_, crease_lines_, corner_lines_, hole_lines_;
  bool faces_have_uvs_ = false;
  bool warned_w_ = false;
  std::set<std::string> warned_;
  bool chunk_ = false;
  int first_line_ = 1;
};

// Chunks of about this many bytes are parsed in parallel; a smaller text is parsed whole.
constexpr std::size_t kChunkBytes = std::size_t(1) << 20;

// The text parsed in chunks that end at line ends, in parallel, and appended in order; nullopt where
// a chunk holds what only the whole text's parse handles (tags, warnings, relative indices, continued
// lines) or an error (whose message the serial parse then gives, naming the right face and line).
std::optional<ObjParser> parse_in_chunks(std::string_view text, const std::string& name) {
  std::vector<std::size_t> starts{0};
  while (text.size() - starts.back() > 2 * kChunkBytes) {
    const std::size_t end = text.find('\n', starts.back() + kChunkBytes);
    if (end == std::string_view::npos) break;
    starts.push_back(end + 1);
  }
  if (starts.size() < 2) return std::nullopt;
  // Each chunk is parsed from its own line 1 and counts its lines; its faces' line numbers are moved on
  // by the lines before it as it is appended.
  std::vector<int> lines(starts.size(), 0);
  std::vector<std::optional<ObjParser>> parts(starts.size());
  std::atomic<bool> unchunkable = false;
  tbb::parallel_for(std::size_t(0), starts.size(), [&](std::size_t c) {
    if (unchunkable) return;
    const std::size_t end = c + 1 < starts.size() ? starts[c + 1] : text.size();
    const std::string_view part = text.substr(starts[c], end - starts[c]);
    lines[c] = int(std::count(part.begin(), part.end(), '\n'));
    try {
      parts[c] = ObjParser::chunk(part, name, 1);
    } catch (const ObjParser::Unchunkable&) {
      unchunkable = true;
    } catch (const CageError&) {
      unchunkable = true;
    }
  });
  if (unchunkable) return std::nullopt;
  std::optional<ObjParser> whole = std::move(parts[0]);
  whole->reserve_for(std::span<const std::optional<ObjParser>>(parts).subspan(1));
  try {
    int before = lines[0];
    for (std::size_t c = 1; c < parts.size(); ++c) {
      whole->append(std::move(*parts[c]), before);
      before += lines[c];
    }
  } catch (const ObjParser::Unchunkable&) {
    return std::nullopt;
  }
  return whole;
}

}  // namespace

Cage parse_obj_cage(std::string_view text, std::string name, ObjParse how) {
  std::optional<ObjParser> chunks;
  if (how == ObjParse::chunks) chunks = parse_in_chunks(text, name);
  Cage cage = chunks ? chunks->finished() : ObjParser(text, std::move(name)).run();
  split_non_manifold(cage);
  return cage;
}

Cage load_obj_cage(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw CageError(path + ": is a directory, not a cage file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CageError(path + ": cannot open the file");
  // Read whole, in one call (a stream buffer's copy into a string stream costs as much as the parse).
  std::string text;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) {
    text.resize(std::size_t(size));
    in.read(text.data(), std::streamsize(size));
    text.resize(std::size_t(in.gcount()));
  }
  if (ec || in.bad()) throw CageError(path + ": cannot read the file");
  return parse_obj_cage(text, path);
}

namespace {

void append_float(std::string& out, float x) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, x);  // shortest text that reads back exactly
  out.append(buffer, r.ptr);
}

}  // namespace

std::string format_obj_cage(const Cage& cage) {
  std::string out = "# written by tessera\n";
  for (const glm::vec3& p : cage.positions) {
    out += "v";
    for (int k = 0; k < 3; ++k) out += ' ', append_float(out, p[k]);
    out += '\n';
  }
  for (const glm::vec2& t : cage.uvs) {
    out += "vt";
    for (int k = 0; k < 2; ++k) out += ' ', append_float(out, t[k]);
    out += '\n';
  }
  for (int f = 0; f < cage.face_count(); ++f) {
    out += 'f';
    for (int k = 0; k < cage.face_sizes[f]; ++k) {
      const int i = cage.face_offsets[f] + k;
      out += ' ' + std::to_string(cage.face_vertices[i] + 1);
      if (cage.has_uvs()) out += '/' + std::to_string(cage.face_uvs[i] + 1);
    }
    out += '\n';
  }
  const CageTags& t = cage.tags;
  for (const Crease& c : t.creases) {
    out += "t crease 2/1/0 " + std::to_string(c.v0) + ' ' + std::to_string(c.v1) + ' ';
    append_float(out, c.sharpness);
    out += '\n';
  }
  for (const Corner& c : t.corners) {
    out += "t corner 1/1/0 " + std::to_string(c.vertex) + ' ';
    append_float(out, c.sharpness);
    out += '\n';
  }
  for (int h : t.holes) out += "t hole 1/0/0 " + std::to_string(h) + '\n';
  if (t.boundary != BoundaryInterpolation::edge_only)
    out += std::string("t interpolateboundary 1/0/0 ") + (t.boundary == BoundaryInterpolation::none ? "0" : "1") + '\n';
  if (t.crease_method == CreaseMethod::chaikin) out += "t creasemethod 0/0/1 chaikin\n";
  if (t.smooth_triangles) out += "t smoothtriangles 0/0/1 smooth\n";
  if (t.fvar_boundary != 1) out += "t facevaryinginterpolateboundary 1/0/0 " + std::to_string(t.fvar_boundary) + '\n';
  if (t.fvar_propagate_corners) out += "t facevaryingpropagatecorners 1/0/0 1\n";
  return out;
}

}  // namespace tessera
