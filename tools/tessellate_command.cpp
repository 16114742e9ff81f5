// `tessera tessellate CAGE.obj --scheme S -o out.ply`: IA -> VS -> HS -> TS -> DS over a cage, and what
// the domain shader produced written as binary PLY. Each patch writes its own vertices (nothing is
// merged across patches), so crack-freedom can be checked from outside by welding on exact float bits;
// `--check-watertight` does that here too.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <type_traits>

#include "cli_common.h"
#include "commands.h"
#include "subd_model.h"
#include "tessellate_options.h"
#include "weld_check.h"

namespace tessera::cli {
namespace {

struct TessellateOptions {
  std::string cage, output, scheme = "gregory", partitioning = "integer", factors_file;
  float factor = 8.0f, vary = 0.0f;
  int threads = 0;
  bool check = false, json = false;
  DisplacementCli displacement;
};

// One PLY value appended to a patch's records, little-endian as the header says, whatever the host's
// byte order. A patch's records go to the file in one write: a stream write per value took as long
// as the tessellation itself.
template <class T>
void put(std::string& out, const T& v) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::array<char, sizeof(T)> bytes;
  std::memcpy(bytes.data(), &v, sizeof v);
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes.begin(), bytes.end());
  out.append(bytes.data(), bytes.size());
}

int run_tessellate(const TessellateOptions& o) {
  const Scheme scheme = scheme_option(o.scheme);
  const ts::Partitioning partitioning = partitioning_option(o.partitioning);
  SubdFactors factors = factors_option(o.factor, o.vary, o.factors_file);
  if (o.output.empty() && !o.check) throw UsageError("nothing to do: give -o out.ply and/or --check-watertight");

  const SubdModel model = load_model(o.cage, scheme);
  const std::optional<Displacement> displacement = displacement_option(o.displacement, model);
  if (model.patches.fallback_faces > 0)
    log_info("bspline: " + std::to_string(model.patches.fallback_faces) +
             " faces are not regular and are drawn as Gregory patches");
  log_debug(std::to_string(model.patches.quads.size() + model.patches.tris.size()) + " patches, " +
            std::to_string(model.patches.tables.size()) + " stencil tables");

  Device device(device_options(o.threads));
  WeldChecker weld;
  std::uint64_t vertices = 0, triangles = 0;
  DrawResult result;
  std::string vbuf, fbuf;  // one patch's vertex and face records
  auto tessellate = [&](std::ofstream* vout, std::ofstream* fout) {
    auto sink = [&](const auto& p, const PatchGroup&) {
      const std::uint64_t base = vertices;
      vbuf.clear(), fbuf.clear();
      if (vout)
        for (const auto& s : p.points) {
          put(vbuf, s.position.x), put(vbuf, s.position.y), put(vbuf, s.position.z);
          put(vbuf, s.normal.x), put(vbuf, s.normal.y), put(vbuf, s.normal.z);
          put(vbuf, std::int32_t(s.face));
          put(vbuf, s.u), put(vbuf, s.v);
        }
      for (std::size_t i = 0; i + 2 < p.indices.size(); i += 3) {
        if (fout) {
          put(fbuf, std::uint8_t(3));
          for (int k = 0; k < 3; ++k) put(fbuf, std::int32_t(base + p.indices[i + std::size_t(k)]));
        }
        if (o.check)
          weld.add_triangle(p.points[p.indices[i]].position, p.points[p.indices[i + 1]].position,
                            p.points[p.indices[i + 2]].position);
        ++triangles;
      }
      if (vout) vout->write(vbuf.data(), std::streamsize(vbuf.size()));
      if (fout) fout->write(fbuf.data(), std::streamsize(fbuf.size()));
      vertices += p.points.size();
    };
    result = displacement ? stream_displaced(device, model, *displacement, factors, partitioning, sink)
                          : stream_subd(device, model, factors, partitioning, sink);
    if (!result.ok()) throw InputError(o.cage + ": " + result.error);
  };

  if (!o.output.empty()) {
    write_file_atomically(o.output, [&](const std::string& temp) {
      // Vertex and face records stream to two side files; the PLY is the header plus both.
      const std::string vpath = temp + ".vertices", fpath = temp + ".faces";
      struct Cleanup {
        std::string a, b;
        ~Cleanup() {
          std::error_code ignored;
          std::filesystem::remove(a, ignored);
          std::filesystem::remove(b, ignored);
        }
      } cleanup{vpath, fpath};
      {
        std::ofstream vout(vpath, std::ios::binary), fout(fpath, std::ios::binary);
        if (!vout || !fout) throw InputError(o.output + ": cannot write");
        tessellate(&vout, &fout);
        if (!vout.flush() || !fout.flush()) throw InputError(o.output + ": write failed");
      }
      std::ofstream out(temp, std::ios::binary);
      out << "ply\nformat binary_little_endian 1.0\ncomment tessera tessellate " << std::filesystem::path(o.cage).filename().string()
           << " scheme " << to_string(scheme)
          << (displacement ? " displacement " + std::filesystem::path(o.displacement.map).filename().string() : std::string())
          << " factor " << float_text(o.factor) << " partitioning " << o.partitioning
          << "\ncomment each patch writes its own vertices; face = base face, u v = domain location\nelement vertex "
          << vertices
          << "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
             "property int face\nproperty float u\nproperty float v\nelement face "
          << triangles << "\nproperty list uchar int vertex_indices\nend_header\n";
      for (const std::string& part : {vpath, fpath}) {
        std::ifstream in(part, std::ios::binary);
        out << in.rdbuf();
      }
      out.close();
      if (!out) throw InputError(o.output + ": write failed");
    });
  } else {
    tessellate(nullptr, nullptr);
  }

  const auto& st = result.report.statistics;
  std::ostringstream text;
  text << o.cage << ": scheme " << to_string(scheme) << ", " << model.patches.quads.size() + model.patches.tris.size()
       << " patches, " << model.patches.tables.size() << " stencil tables, " << st.DSInvocations << " domain points, "
       << triangles << " triangles";
  WeldReport w;
  if (o.check) w = weld.report();
  if (o.json) {
    std::cout << "{\"cage\": " << json_quoted(o.cage) << ", \"scheme\": \"" << to_string(scheme) << "\", \"patches\": "
              << model.patches.quads.size() + model.patches.tris.size() << ", \"stencil_tables\": " << model.patches.tables.size()
              << ", \"fallback_faces\": " << model.patches.fallback_faces << ", \"vertices\": " << vertices
              << ", \"triangles\": " << triangles << ", \"hs_invocations\": " << st.HSInvocations
              << ", \"ds_invocations\": " << st.DSInvocations << ", \"seconds\": " << result.report.times.wall;
    if (o.check) std::cout << ", \"watertight\": " << w.to_json();
    std::cout << "}\n";
  } else {
    std::cout << text.str() << "\n";
    if (o.check) std::cout << w.summary() << "\n";
  }
  return o.check && !w.closed_manifold() ? kExitFailure : kExitOk;
}

}  // namespace

Runner add_tessellate_command(CLI::App& app) {
  auto o = std::make_shared<TessellateOptions>();
  CLI::App* cmd = app.add_subcommand("tessellate", "run IA..DS over a cage and write the DS output as PLY");
  cmd->add_option("cage", o->cage, "the cage (OBJ, OpenSubdiv tags allowed)")->required();
  cmd->add_option("-o,--output", o->output, "output PLY (binary; each patch its own vertices)");
  add_scheme_options(*cmd, o->scheme, o->factor, o->vary, o->factors_file, o->partitioning, o->threads);
  add_displacement_options(*cmd, o->displacement);
  cmd->add_flag("--check-watertight", o->check, "weld on exact bits and check for a closed 2-manifold (exit 1 if not)");
  cmd->add_flag("--json", o->json, "print the summary as JSON");
  return [o] { return run_tessellate(*o); };
}

}  // namespace tessera::cli
