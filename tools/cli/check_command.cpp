// `tessera check SUITE`: renders a golden suite's scenes (check_suite.h), compares them with their
// goldens, and writes report.html, junit.xml and summary.json (check_report.h). Exit 0 when every case
// passes (warnings pass). Goldens are written only with --update or TESSERA_UPDATE_GOLDEN=1, and only
// for failed and new cases, each named on stderr. --shard I/N runs one share; --merge joins shards.
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <filesystem>
#include <iostream>
#include <regex>

#include "tools/cli/commands.h"
#include "tools/scene/check_report.h"
#include "tools/scene/check_suite.h"
#include "tools/scene/common.h"

namespace tessera::cli {

using namespace scene;

namespace {

namespace fs = std::filesystem;

struct CheckOptions {
  std::string suite, report = "check-report", shard;
  std::vector<std::string> merge;
  bool update = false, json = false, collect_assets = false;
  int threads = -1;  // -1: each scene file's own (its default: all cores)
};

// Copies a file into the report directory (the report stands alone as a CI artifact).
void copy_into(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::create_directories(to.parent_path(), ec);
  fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
  if (ec) throw InputError(to.string() + ": cannot write (" + ec.message() + ")");
}

std::string text_of_counts(const Json& n) {
  std::string out;
  for (const auto& [status, count] : n.items())
    if (count.get<int>() > 0) out += (out.empty() ? "" : ", ") + std::to_string(count.get<int>()) + " " + status;
  return out.empty() ? "no cases" : out;
}

int finish(const Json& summary, const CheckOptions& o) {
  write_check_reports(summary, o.report);
  const Json& n = summary["counts"];
  const int bad = n["fail"].get<int>() + n["new"].get<int>() + n["error"].get<int>();
  if (o.json) {
    std::cout << json_text(summary) << "\n";
  } else {
    std::cout << text_of_counts(n) << " -> " << (fs::path(o.report) / "report.html").string() << "\n";
  }
  // What to do next, on stderr: a new case has no golden until --update writes one, and a failed case
  // is either a regression or an intended change to bless.
  const int fresh = n["new"].get<int>(), failed = n["fail"].get<int>();
  if ((fresh > 0 || failed > 0) && o.merge.empty()) {
    const std::string what = fresh > 0 && failed > 0 ? "the new cases' images and the failed cases' changes"
                             : fresh > 0             ? "the new cases' images"
                                                     : "the failed cases' changes";
    std::cerr << "tessera check: look at " << what << " in " << (fs::path(o.report) / "report.html").string()
              << "; if they are right, `tessera check " << o.suite << " --update` writes their goldens\n";
  }
  return bad == 0 ? kExitOk : kExitFailure;
}

int run_merge(const CheckOptions& o) {
  Json cases = Json::array();
  std::string suite;
  double seconds = 0;
  for (const std::string& dir : o.merge) {
    const fs::path path = fs::path(dir) / "summary.json";
    std::ifstream in(path);
    if (!in) throw InputError(path.string() + ": cannot read (a tessera check report directory?)");
    Json s;
    try {
      s = Json::parse(in);
    } catch (const Json::exception&) {
      throw InputError(path.string() + ": not JSON");
    }
    if (!s.contains("cases") || !s.contains("suite")) throw InputError(path.string() + ": not a check summary");
    if (!suite.empty() && s["suite"] != suite)
      throw InputError(path.string() + ": suite '" + s["suite"].get<std::string>() + "', not '" + suite + "'");
    suite = s["suite"].get<std::string>();
    seconds += s["seconds"].get<double>();
    for (const Json& c : s["cases"]) {
      for (const char* key : {"new_image", "diff_image"}) {
        const std::string rel = c[key].get<std::string>();
        if (!rel.empty()) copy_into(fs::path(dir) / rel, fs::path(o.report) / rel);
      }
      if (c.value("report_golden", false)) {
        const std::string rel = "golden/" + c["name"].get<std::string>() + ".png";
        copy_into(fs::path(dir) / rel, fs::path(o.report) / rel);
      }
      cases.push_back(c);
    }
  }
  std::sort(cases.begin(), cases.end(), [](const Json& a, const Json& b) { return a["index"] < b["index"]; });
  for (std::size_t i = 1; i < cases.size(); ++i)
    if (cases[i]["index"] == cases[i - 1]["index"])
      throw InputError("case '" + cases[i]["name"].get<std::string>() + "' is in two of the merged reports");
  const Json summary = {
      {"suite", suite}, {"shard", "merged"}, {"cases", cases}, {"counts", count_statuses(cases)}, {"seconds", seconds}};
  return finish(summary, o);
}

int run_check(const CheckOptions& o) {
  if (!o.merge.empty()) {
    if (!o.suite.empty() || o.update || !o.shard.empty())
      throw UsageError("--merge joins reports: no SUITE, --update or --shard with it");
    return run_merge(o);
  }
  if (o.suite.empty()) throw UsageError("give a SUITE file (or --merge DIR...)");
  if (o.collect_assets) {
    for (const std::string& line : collect_suite_assets(read_suite(o.suite))) log_info(line);
    return kExitOk;
  }
  if (o.threads < -1 || o.threads > 4096) throw UsageError("--threads: expected 0..4096 (0: all cores)");
  int shard = 1, shards = 1;
  if (!o.shard.empty()) {
    std::smatch m;
    const std::regex re(R"((\d{1,4})/(\d{1,4}))");
    if (!std::regex_match(o.shard, m, re) || std::stoi(m[1]) < 1 || std::stoi(m[1]) > std::stoi(m[2]))
      throw UsageError("--shard: expected I/N with 1 <= I <= N, got '" + o.shard + "'");
    shard = std::stoi(m[1]), shards = std::stoi(m[2]);
  }
  const char* env = std::getenv("TESSERA_UPDATE_GOLDEN");
  const bool update = o.update || (env && std::string(env) == "1");
  const Suite suite = read_suite(o.suite);
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < suite.cases.size(); ++i)
    if (int(i % std::size_t(shards)) == shard - 1) mine.push_back(i);

  fs::create_directories(o.report);
  Json cases = Json::array();
  double seconds = 0;
  int done = 0;
  for (const std::size_t i : mine) {
    const SuiteCase& c = suite.cases[i];
    CaseResult r = run_case(suite, c, o.report, o.threads);
    ++done;
    log_info("[" + std::to_string(done) + "/" + std::to_string(mine.size()) + "] " + c.name + ": " +
             to_string(r.status) + (r.message.empty() ? "" : " (" + r.message + ")"));
    if (update && (r.status == CaseStatus::fail || r.status == CaseStatus::new_case)) {
      bless_case(suite, c, r, o.report);
      std::cerr << "tessera check: updated the golden of " << c.name << " (was " << to_string(r.status)
                << (r.message.empty() ? "" : ": " + r.message) << ")\n";
      r.status = CaseStatus::pass;
      r.message = "golden updated";
    } else if (update && r.status != CaseStatus::error && r.scene_changes.is_null()) {
      // A golden blessed before goldens recorded their scene: its image and digest stand, the scene is added.
      record_golden_scene(suite, c, r);
      std::cerr << "tessera check: recorded the scene of " << c.name << "'s golden\n";
    }
    Json j = r.json();
    j["index"] = i;
    const bool golden_exists = fs::exists(r.golden_image);
    if (golden_exists) copy_into(r.golden_image, fs::path(o.report) / "golden" / (c.name + ".png"));
    j["report_golden"] = golden_exists;
    cases.push_back(j);
    seconds += r.seconds;
  }
  const Json summary = {{"suite", suite.name},
                        {"suite_path", fs::absolute(suite.path).lexically_normal().string()},
                        {"shard", std::to_string(shard) + "/" + std::to_string(shards)},
                        {"cases", cases},
                        {"counts", count_statuses(cases)},
                        {"seconds", seconds}};
  return finish(summary, o);
}

}  // namespace

Runner add_check_command(CLI::App& app) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check", "render a golden suite's scenes, compare with the goldens, write report.html, junit.xml, summary.json");
  cmd->add_option("suite", o->suite, "the suite file (JSON: cases of scene, compare, checks)");
  cmd->add_option("-o,--report", o->report, "the report directory")->capture_default_str();
  cmd->add_flag("--update", o->update,
                "write the goldens of failed and new cases from this run (also TESSERA_UPDATE_GOLDEN=1); says which");
  cmd->add_flag("--collect-assets", o->collect_assets,
                "copy the files the suite's scenes name into assets/ beside the suite and point the scenes there, "
                "so the suite runs wherever it is copied");
  cmd->add_option("--shard", o->shard, "I/N: run only cases I, I+N, I+2N, ... (1-based), for spreading a suite");
  cmd->add_option("--merge", o->merge, "join the report directories of shards into -o")->expected(1, -1);
  cmd->add_flag("--json", o->json, "print the summary as JSON");
  cmd->add_option("--threads", o->threads,
                  "worker threads for every case, 0 = all cores (default: each scene file's; the bytes do not "
                  "depend on it, the time does)");
  return [o, cmd]() -> int { return cmd->parsed() ? run_check(*o) : -1; };
}

}  // namespace tessera::cli
