// Tessellates a cube cage as Gregory ACC patches through the installed Tessera libraries and welds
// the result on exact bits; prints "<patches> <triangles> <watertight>" for the test to check. With
// an argument, also writes a small PNG there (the installed image module, loaded at run time).
#include <cstdio>

#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/image_io/image_file.h"
#include "shaders_cpp/render/subd_model.h"
#include "tessellator/tessellator.h"
#include "tools/verify/weld_check.h"

int main(int argc, char** argv) {
  using namespace tessera;
  const char* cube =
      "v -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 -1\nv 1 -1 -1\n"
      "f 1 2 4 3\nf 3 4 6 5\nf 5 6 8 7\nf 7 8 2 1\nf 2 8 6 4\nf 7 1 3 5\n";
  const SubdModel model = make_subd_model(parse_obj_cage(cube, "cube"), Scheme::gregory);
  Device device(DeviceOptions{.threads = 2});
  SubdFactors factors;
  factors.factor = 4.0f;
  verify::WeldChecker weld;
  const DrawResult r =
      stream_subd(device, model, factors, ts::Partitioning::integer, [&](const auto& p, const PatchGroup&) {
        for (std::size_t i = 0; i + 2 < p.indices.size(); i += 3)
          weld.add_triangle(p.points[p.indices[i]].position, p.points[p.indices[i + 1]].position,
                            p.points[p.indices[i + 2]].position);
      });
  if (!r.ok()) {
    std::fprintf(stderr, "consumer: %s\n", r.error.c_str());
    return 1;
  }
  if (argc > 1) {
    std::string error;
    auto fb = Framebuffer::create(8, 4, ColorFormat::rgba8_unorm, &error);
    if (fb) error = write_color(*fb, {argv[1]});
    if (!error.empty()) {
      std::fprintf(stderr, "consumer: %s\n", error.c_str());
      return 1;
    }
  }
  const verify::WeldReport w = weld.report();
  std::printf("%zu %llu %s\n", model.patches.quads.patches.size(), static_cast<unsigned long long>(w.triangles),
              w.closed_manifold() ? "watertight" : "cracked");
  return 0;
}
