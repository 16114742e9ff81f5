// (b) A draw written from scratch: your own patch list, vertex, hull, domain and pixel shaders, as C++
// functors the pipeline calls directly (pipeline/stage_io.h lists the shapes). The surface is a
// parametric torus cut into a grid of quad patches, one control point each (its cell); the domain
// shader evaluates the torus at the cell's parameters and the pixel shader shades it with a stripe
// per cell. Writes parametric_torus.png.
//
// Watertight by construction: a point on a shared edge gets its parameter as float(cell) + u with u
// exactly 0 or 1 there, so both cells compute the same float and so the same position bits.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/device.h"
#include "shaders_cpp/image_io/image_file.h"

using namespace tessera;

constexpr int kAround = 16, kAcross = 8;  // cells
constexpr float kMajor = 2.0f, kMinor = 0.75f;

// Vertex shader: the control point (a cell's column and row) passes through.
struct CellVS {
  glm::vec2 operator()(const glm::vec2& cell, std::uint32_t) const { return cell; }
};

// Hull shader: one output control point, the cell; every factor the same.
struct TorusConstants {
  TessFactors factors;
};
struct TorusHS {
  static constexpr int kOutputControlPoints = 1;
  float factor = 8.0f;
  glm::vec2 control_point(std::span<const glm::vec2> in, int, std::uint32_t) const { return in[0]; }
  TorusConstants patch_constants(std::span<const glm::vec2>, std::span<const glm::vec2>, std::uint32_t) const {
    TorusConstants pc;
    pc.factors.edge = {factor, factor, factor, factor};
    pc.factors.inside = {factor, factor};
    return pc;
  }
};

// Domain shader: the torus at the cell's parameters; clip position, the normal, and which cell.
struct TorusDS {
  glm::mat4 view_projection{1.0f};
  ClipVertex<4> operator()(const TorusConstants&, std::span<const glm::vec2> cell, DomainLocation loc,
                           std::uint32_t) const {
    const float s = (cell[0].x + loc.u) / float(kAround), t = (cell[0].y + loc.v) / float(kAcross);
    const float a = 2.0f * std::numbers::pi_v<float> * s, b = 2.0f * std::numbers::pi_v<float> * t;
    const glm::vec3 n(std::cos(a) * std::cos(b), std::sin(b), std::sin(a) * std::cos(b));
    const glm::vec3 p = glm::vec3(kMajor * std::cos(a), 0.0f, kMajor * std::sin(a)) + kMinor * n;
    ClipVertex<4> out;
    out.position = view_projection * glm::vec4(p, 1.0f);
    out.attributes = {n.x, n.y, n.z, cell[0].x + cell[0].y};
    return out;
  }
};

// Pixel shader: a headlight on the interpolated normal, alternate cells a little darker.
struct TorusPS {
  glm::vec3 light{0.0f, 0.0f, 1.0f};
  glm::vec4 operator()(const PixelInput<4>& in) const {
    const glm::vec3 n = glm::normalize(glm::vec3(in.attributes[0], in.attributes[1], in.attributes[2]));
    const float lit = 0.25f + 0.75f * std::abs(glm::dot(n, light));
    const bool odd = int(std::lround(in.attributes[3])) % 2 != 0;
    const glm::vec3 base = odd ? glm::vec3(0.85f, 0.55f, 0.35f) : glm::vec3(0.95f, 0.75f, 0.5f);
    return glm::vec4(base * lit, 1.0f);
  }
};

int main() {
  const int width = 800, height = 500;
  std::vector<glm::vec2> cells;
  std::vector<std::uint32_t> indices;
  for (int j = 0; j < kAcross; ++j)
    for (int i = 0; i < kAround; ++i) {
      indices.push_back(std::uint32_t(cells.size()));
      cells.emplace_back(float(i), float(j));
    }
  const glm::vec3 eye(0.0f, 4.0f, 6.5f);
  const glm::mat4 view_projection =
      glm::perspectiveRH_ZO(glm::radians(35.0f), float(width) / float(height), 0.1f, 50.0f) *
      glm::lookAtRH(eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));

  PatchDraw<glm::vec2, CellVS, TorusHS, TorusDS, TorusPS> draw;
  draw.vertices = cells;
  draw.indices = indices;
  draw.control_points = 1;
  draw.ds.view_projection = view_projection;
  draw.ps.light = glm::normalize(eye);
  draw.tessellator = {ts::Domain::quad, ts::Partitioning::integer, ts::OutputPrimitive::triangle_cw};
  draw.rasterizer.cull = CullMode::none;  // both sides: the shader lights |n . l|
  draw.viewport = {0.0f, 0.0f, float(width), float(height)};

  Device device(DeviceOptions{.threads = 0});
  std::string error;
  auto fb = Framebuffer::create(width, height, ColorFormat::rgba8_unorm, &error);
  if (!fb) return std::fprintf(stderr, "parametric_torus: %s\n", error.c_str()), 1;
  device.clear(*fb, glm::vec4(0.93f, 0.94f, 0.96f, 1.0f), 1.0f);
  const DrawResult r = device.draw(draw, *fb);
  if (!r.ok()) return std::fprintf(stderr, "parametric_torus: %s\n", r.error.c_str()), 1;
  error = write_color(*fb, {"parametric_torus.png"});
  if (!error.empty()) return std::fprintf(stderr, "parametric_torus: %s\n", error.c_str()), 1;
  std::printf("parametric_torus.png: %llu patches, %llu domain points, %llu pixels shaded\n",
              static_cast<unsigned long long>(r.report.statistics.HSInvocations),
              static_cast<unsigned long long>(r.report.statistics.DSInvocations),
              static_cast<unsigned long long>(r.report.statistics.PSInvocations));
  return 0;
}
