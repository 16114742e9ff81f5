#include "shaders_cpp/subdiv/single_crease_basis.h"

#include <algorithm>

namespace tessera::subdiv {

void cubic_bspline_basis(double x, double w[4], double dw[4]) {
  const double y = 1.0 - x, x2 = x * x;
  w[0] = y * y * y / 6.0;
  w[1] = (4.0 - 6.0 * x2 + 3.0 * x2 * x) / 6.0;
  w[2] = (1.0 + 3.0 * x + 3.0 * x2 - 3.0 * x2 * x) / 6.0;
  w[3] = x2 * x / 6.0;
  dw[0] = -0.5 * y * y;
  dw[1] = 1.5 * x2 - 2.0 * x;
  dw[2] = 0.5 + x - 1.5 * x2;
  dw[3] = 0.5 * x2;
}

void crease_curve_basis(double x, double sharpness, double w[4], double dw[4]) {
  // m[i][j]: weight of row Qj in the current span's point i; the span runs from point 1 to point 2.
  double m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  double scale = 1.0;
  for (double left = sharpness; left > 0.0; left -= 1.0) {
    const double sharp = std::min(left, 1.0);  // the crease vertex rule's share at this step
    double n[5][4];                            // E01, V1, E12, V2, E23 of the current points
    for (int j = 0; j < 4; ++j) {
      const double a = m[0][j], b = m[1][j], c = m[2][j], d = m[3][j];
      n[0][j] = 0.5 * (a + b);
      n[1][j] = (a + 6.0 * b + c) / 8.0;
      n[2][j] = 0.5 * (b + c);
      n[3][j] = (1.0 - sharp) * ((b + 6.0 * c + d) / 8.0) + sharp * c;
      n[4][j] = 0.5 * (c + d);
    }
    scale *= 2.0;
    // The half away from the crease (E01, V1, E12, V2) is a plain B-spline segment: stop there.
    const int first = x < 0.5 ? 0 : 1;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) m[i][j] = n[first + i][j];
    x = x < 0.5 ? 2.0 * x : 2.0 * x - 1.0;
    if (first == 0) break;
  }
  double b[4], db[4];
  cubic_bspline_basis(x, b, db);
  for (int j = 0; j < 4; ++j) {
    w[j] = b[0] * m[0][j] + b[1] * m[1][j] + b[2] * m[2][j] + b[3] * m[3][j];
    dw[j] = scale * (db[0] * m[0][j] + db[1] * m[1][j] + db[2] * m[2][j] + db[3] * m[3][j]);
  }
}

namespace {

// A phantom point beyond the end of a row (boundary): 2 * inner - next, folded into those two.
void fold(double w[4], int phantom, int inner, int next) {
  w[inner] += 2.0 * w[phantom];
  w[next] -= w[phantom];
  w[phantom] = 0.0;
}

}  // namespace

RegularCurves regular_patch_curves(int boundary, double s, double t) {
  RegularCurves c;
  cubic_bspline_basis(s, c.s, c.ds);
  cubic_bspline_basis(t, c.t, c.dt);
  for (double* w : {c.t, c.dt}) {
    if (boundary & 1) fold(w, 0, 1, 2);  // t = 0
    if (boundary & 4) fold(w, 3, 2, 1);  // t = 1
  }
  for (double* w : {c.s, c.ds}) {
    if (boundary & 8) fold(w, 0, 1, 2);  // s = 0
    if (boundary & 2) fold(w, 3, 2, 1);  // s = 1
  }
  return c;
}

RegularCurves single_crease_curves(int edge, double sharpness, double s, double t) {
  // The crease runs along s (edges 0, 2) or along t (edges 1, 3); on edges 0 and 3 it lies at the
  // parameter's 0, so the curve runs reversed (rows 3..0, x = 1 - parameter, derivative negated).
  const bool across_t = edge == 0 || edge == 2, reversed = edge == 0 || edge == 3;
  const double across = across_t ? t : s, along = across_t ? s : t;
  double a[4], da[4], c[4], dc[4];
  cubic_bspline_basis(along, a, da);
  crease_curve_basis(reversed ? 1.0 - across : across, sharpness, c, dc);
  if (reversed) {
    std::swap(c[0], c[3]);
    std::swap(c[1], c[2]);
    std::swap(dc[0], dc[3]);
    std::swap(dc[1], dc[2]);
    for (double& d : dc) d = -d;
  }
  RegularCurves r;
  for (int k = 0; k < 4; ++k) {
    r.s[k] = across_t ? a[k] : c[k];
    r.ds[k] = across_t ? da[k] : dc[k];
    r.t[k] = across_t ? c[k] : a[k];
    r.dt[k] = across_t ? dc[k] : da[k];
  }
  return r;
}

}  // namespace tessera::subdiv
