// `tessera make-cage torus --grid AxB -o cage.obj` or `make-cage sphere --pole-valence N -o cage.obj`:
// writes a synthetic control cage (cage_generators.h) as OBJ with UVs, for measurements no bundled asset
// allows (the memory table's large cage; the ripples around a pole of any valence, quad or polar).
#include <iostream>
#include <memory>
#include <stdexcept>

#include "shaders_cpp/cage/cage_generators.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "tools/cli/commands.h"
#include "tools/scene/common.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct MakeCageOptions {
  std::string shape = "torus", grid = "128x64", output;
  float major = 1.0f, minor = 0.35f, radius = 1.0f;
  int pole_valence = 8, bands = 8;
  bool polar = false;
};

int run_make_cage(const MakeCageOptions& o) {
  if (o.shape != "torus" && o.shape != "sphere")
    throw UsageError("make-cage: unknown shape '" + o.shape + "' (known: torus, sphere)");
  if (o.output.empty()) throw UsageError("-o cage.obj is required");
  Cage cage;
  try {
    if (o.shape == "sphere") {
      cage = sphere_cage(o.pole_valence, o.bands, o.radius, o.polar);
    } else {
      const auto [around, across] = parse_size(o.grid, "--grid", 3, 4096);
      cage = torus_cage(around, across, o.major, o.minor);
    }
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  write_text_atomically(o.output, format_obj_cage(cage));
  std::cout << o.output << ": " << cage.name << ", " << cage.vertex_count() << " vertices, " << cage.face_count()
            << " faces\n";
  return kExitOk;
}

}  // namespace

Runner add_make_cage_command(CLI::App& app) {
  auto o = std::make_shared<MakeCageOptions>();
  CLI::App* cmd =
      app.add_subcommand("make-cage", "write a synthetic control cage (OBJ with UVs) for scaling measurements");
  cmd->add_option("shape", o->shape, "the shape: torus or sphere (two poles of --pole-valence)")->capture_default_str();
  cmd->add_option("--grid", o->grid, "faces around x across (each 3..4096)")->capture_default_str();
  cmd->add_option("--major-radius", o->major, "torus: distance from the centre to the tube's centre")
      ->capture_default_str();
  cmd->add_option("--minor-radius", o->minor, "torus: the tube's radius")->capture_default_str();
  cmd->add_option("--pole-valence", o->pole_valence, "sphere: the valence of both poles (3..2048)")
      ->capture_default_str();
  cmd->add_option("--bands", o->bands, "sphere: bands of latitude from pole to pole (2..4096)")->capture_default_str();
  cmd->add_option("--radius", o->radius, "sphere: its radius")->capture_default_str();
  cmd->add_flag("--polar", o->polar,
                "sphere: latitude-longitude, --pole-valence vertices per latitude and a fan of triangles at each "
                "pole (a polar configuration) instead of all quads");
  cmd->add_option("-o,--output", o->output, "the OBJ file to write");
  return [o] { return run_make_cage(*o); };
}

}  // namespace tessera::cli
