// `tessera bench`: benchmarks (never timed tests). `bench tessellator` measures the
// fixed-function tessellator alone on a mix of domains, partitionings and factors.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>

#include "tessellator/tessellator.h"
#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct BenchOptions {
  double seconds = 2.0;
  bool json = false;
};

struct Workload {
  std::string name;
  ts::Partitioning partitioning;
  std::vector<ts::FactorSet> patches;
};

// Patches around a nominal factor, with per-edge variation as a real mesh has.
Workload make_workload(ts::Domain domain, ts::Partitioning p, float factor, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(0.75f, 1.0f);
  Workload w{
      std::string(ts::to_string(domain)) + " " + std::string(ts::to_string(p)) + " ~" + float_text(factor), p, {}};
  for (int i = 0; i < 64; ++i) {
    ts::FactorSet f;
    f.domain = domain;
    for (auto& v : f.values) v = factor * jitter(rng);
    w.patches.push_back(f);
  }
  return w;
}

int run_bench_tessellator(const BenchOptions& o) {
  if (!(o.seconds > 0 && o.seconds <= 3600)) throw UsageError("--seconds: must be in (0, 3600]");
  std::vector<Workload> loads;
  std::uint32_t seed = 1;
  for (ts::Domain d : {ts::Domain::quad, ts::Domain::tri})
    for (ts::Partitioning p :
         {ts::Partitioning::integer, ts::Partitioning::fractional_odd, ts::Partitioning::fractional_even})
      for (float f : {8.0f, 16.0f, 64.0f}) loads.push_back(make_workload(d, p, f, seed++));

  const double per_load = o.seconds / double(loads.size());
  ts::Pattern pattern;
  Json json = {{"benchmark", "tessellator"}, {"threads", 1}, {"workloads", Json::array()}};
  double total_points = 0, total_tris = 0, total_time = 0;
  for (std::size_t li = 0; li < loads.size(); ++li) {
    const auto& w = loads[li];
    std::size_t points = 0, tris = 0, reps = 0;
    const auto start = std::chrono::steady_clock::now();
    double elapsed = 0;
    do {
      for (const auto& f : w.patches) {
        ts::tessellate(w.partitioning, ts::OutputPrimitive::triangle_cw, f, pattern);
        points += pattern.points.size();
        tris += pattern.primitive_count();
      }
      ++reps;
      elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    } while (elapsed < per_load);
    total_points += double(points), total_tris += double(tris), total_time += elapsed;
    const double mpts = double(points) / elapsed / 1e6, mtris = double(tris) / elapsed / 1e6;
    if (!o.json) {
      char line[160];
      std::snprintf(line, sizeof line, "%-34s %8.1f M points/s %8.1f M triangles/s  (%zu patches)\n", w.name.c_str(),
                    mpts, mtris, reps * w.patches.size());
      std::cout << line;
    }
    json["workloads"].push_back(
        {{"name", w.name}, {"points_per_s", double(points) / elapsed}, {"triangles_per_s", double(tris) / elapsed}});
  }
  json["points_per_s"] = total_points / total_time;
  json["triangles_per_s"] = total_tris / total_time;
  if (o.json)
    std::cout << json_text(json) << "\n";
  else {
    char line[160];
    std::snprintf(line, sizeof line, "overall: %.1f M points/s, %.1f M triangles/s on one thread\n",
                  total_points / total_time / 1e6, total_tris / total_time / 1e6);
    std::cout << line;
  }
  return kExitOk;
}

}  // namespace

Runner add_bench_command(CLI::App& app, std::span<const BenchAdder> more) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Benchmarks (results to stdout, --json for scripts)");
  cmd->require_subcommand(1);
  CLI::App* tess = cmd->add_subcommand("tessellator", "Fixed-function tessellator throughput, one thread");
  tess->add_option("--seconds", o->seconds, "total measuring time")->capture_default_str();
  tess->add_flag("--json", o->json, "print results as JSON");
  tess->fallthrough();
  Runner torus = add_bench_torus_command(*cmd);
  Runner frog = add_bench_subd_command(*cmd);
  Runner dolly = add_bench_dolly_command(*cmd);
  Runner scaling = add_bench_scaling_command(*cmd);
  std::vector<Runner> others;
  for (const BenchAdder add : more) others.push_back(add(*cmd));
  return [o, tess, torus, frog, dolly, scaling, others]() -> int {
    if (tess->parsed()) return run_bench_tessellator(*o);
    if (const int rc = torus(); rc >= 0) return rc;
    if (const int rc = frog(); rc >= 0) return rc;
    if (const int rc = dolly(); rc >= 0) return rc;
    if (const int rc = scaling(); rc >= 0) return rc;
    for (const Runner& other : others)
      if (const int rc = other(); rc >= 0) return rc;
    throw UsageError("bench: choose a benchmark (tessellator, torus, frog, dolly, scaling, view, load)");
  };
}

}  // namespace tessera::cli
