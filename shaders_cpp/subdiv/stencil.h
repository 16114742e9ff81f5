// A stencil: a point of a patch as a weighted sum of cage vertices, sum_i w_i * P[v_i].
//
// Stencils are built in double from the schemes' masks and kept sorted by vertex index with one term
// per vertex. That order is the global summation order of the hull shader (the talk's `vertexIndex`
// remap): two patches that compute the same point from the same weights add the same terms in the same
// order, so the point comes out bit-identical on both, which watertight edges need.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

namespace tessera {

struct Stencil {
  std::vector<std::pair<int, double>> terms;  // (vertex, weight), sorted by vertex, unique, weights != 0

  static Stencil vertex(int v) { return Stencil{{{v, 1.0}}}; }

  // Adds w * other, merging terms; drops weights that cancel to exactly zero.
  Stencil& add(const Stencil& other, double w) {
    std::vector<std::pair<int, double>> out;
    out.reserve(terms.size() + other.terms.size());
    std::size_t i = 0, j = 0;
    while (i < terms.size() || j < other.terms.size()) {
      if (j == other.terms.size() || (i < terms.size() && terms[i].first < other.terms[j].first)) {
        out.push_back(terms[i++]);
      } else if (i == terms.size() || other.terms[j].first < terms[i].first) {
        out.emplace_back(other.terms[j].first, w * other.terms[j].second);
        ++j;
      } else {
        const double s = terms[i].second + w * other.terms[j].second;
        if (s != 0.0) out.emplace_back(terms[i].first, s);
        ++i;
        ++j;
      }
    }
    std::erase_if(out, [](const auto& t) { return t.second == 0.0; });
    terms = std::move(out);
    return *this;
  }
  Stencil& add_vertex(int v, double w) { return add(vertex(v), w); }
  Stencil& scale(double s) {
    for (auto& t : terms) t.second *= s;
    return *this;
  }
  double weight_sum() const {
    double s = 0;
    for (const auto& t : terms) s += t.second;
    return s;
  }
};

inline Stencil operator+(Stencil a, const Stencil& b) { return a.add(b, 1.0); }
inline Stencil operator-(Stencil a, const Stencil& b) { return a.add(b, -1.0); }
inline Stencil operator*(double s, Stencil a) { return a.scale(s); }

}  // namespace tessera
