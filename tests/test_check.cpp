// `tessera check` (tools/scene/check_suite.h, check_report.h): Tessera's own view goldens pass; a changed scene
// fails with a diff picture, a JUnit failure and the golden untouched; --update (or
// TESSERA_UPDATE_GOLDEN=1) rewrites only failed and new goldens and says which; shards merge into the
// single run's report; bad suites get one line.
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "test_data.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
const fs::path kSuites = fs::path(TESSERA_GOLDEN_DIR) / "suites";

// A copy of the shipped suite whose scenes name the assets by absolute path, in `dir`.
fs::path copy_suite(const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy(kSuites, dir, fs::copy_options::recursive);
  const std::string data = fs::path(TESSERA_TEST_DATA_DIR).string();
  for (const auto& e : fs::directory_iterator(dir / "scenes")) {
    std::string text = test::slurp(e.path());
    text = std::regex_replace(text, std::regex(R"("(\.\./)+tests/data)"), "\"" + data);
    std::ofstream(e.path()) << text;
  }
  return dir / "views.json";
}

nlohmann::json summary_of(const fs::path& report) {
  return nlohmann::json::parse(test::slurp(report / "summary.json"));
}

}  // namespace

TEST_CASE("Tessera's own view goldens pass tessera check", "[check][cli]") {
  const fs::path report = test::cli_temp_dir() / "check-own";
  const auto r = test::run_cli("check " + (kSuites / "views.json").string() + " -o " + report.string());
  INFO(r.err);
  CHECK(r.exit_code == 0);
  const auto s = summary_of(report);
  CHECK(s["counts"]["pass"] == 5);
  for (const auto& c : s["cases"]) {
    CHECK(c["status"] == "pass");
    CHECK(fs::exists(report / c["new_image"].get<std::string>()));
  }
  CHECK(fs::exists(report / "report.html"));
  CHECK(test::slurp(report / "junit.xml").find("failures=\"0\"") != std::string::npos);
}

TEST_CASE("A changed scene fails with a diff and leaves the golden, --update rewrites and says which", "[check][cli]") {
  const fs::path dir = test::cli_temp_dir() / "check-change";
  const fs::path suite = copy_suite(dir / "suite");
  const fs::path scene = dir / "suite/scenes/frog-acc-wire.json";
  std::string text = test::slurp(scene);
  text = std::regex_replace(text, std::regex(R"("factor": 6\.0)"), "\"factor\": 7.0");
  std::ofstream(scene) << text;
  const fs::path golden = dir / "suite/views/frog-acc-wire.png";
  const std::string before = test::slurp(golden);

  const fs::path report = dir / "report";
  // --threads 1: the same verdict (the bytes do not depend on the thread count).
  const auto r = test::run_cli("check " + suite.string() + " --threads 1 -o " + report.string());
  CHECK(r.exit_code == 1);
  // The next step is named: look at the report, then --update if the change is intended.
  CHECK(r.err.find("the failed cases' changes") != std::string::npos);
  CHECK(r.err.find("check " + suite.string() + " --update") != std::string::npos);
  const auto s = summary_of(report);
  CHECK(s["counts"]["fail"] == 1);
  CHECK(s["counts"]["pass"] == s["cases"].size() - 1);
  const auto& c = s["cases"][1];
  CHECK(c["name"] == "frog-acc-wire");
  CHECK(c["status"] == "fail");
  CHECK(c["checks"]["triangles"]["pass"] == false);
  CHECK(c["compare"]["identical"] == false);
  CHECK(fs::exists(report / c["diff_image"].get<std::string>()));
  CHECK(c["command"].get<std::string>().find("tessera render --scene") == 0);
  // The golden records its scene: the failure names the field that changed, and the report shows it.
  CHECK(c["scene_changes"] == nlohmann::json::parse(R"([{"field": "factor", "golden": 6.0, "new": 7.0}])"));
  CHECK(c["message"].get<std::string>().find("the scene differs from the golden's in factor") != std::string::npos);
  const std::string html = test::slurp(report / "report.html");
  CHECK(html.find("<td>factor</td><td>6.0</td><td>7.0</td>") != std::string::npos);
  // Full size, a wipe slider and a flip for new against golden; metrics to four digits.
  CHECK(html.find("(full size)</a>") != std::string::npos);
  CHECK(html.find("type=\"range\"") != std::string::npos);
  CHECK(html.find("onclick=\"flip(this)\"") != std::string::npos);
  CHECK(!std::regex_search(html, std::regex(R"((max error|mean|RMS|PSNR) [0-9]*\.[0-9]{7,})")));
  const std::string junit = test::slurp(report / "junit.xml");
  CHECK(junit.find("<failure message=\"fail: image:") != std::string::npos);
  CHECK(test::slurp(golden) == before);  // never written without a switch

  const auto u = test::run_cli("check --update " + suite.string() + " -o " + report.string());
  CHECK(u.exit_code == 0);
  CHECK(u.err.find("updated the golden of frog-acc-wire") != std::string::npos);
  CHECK(u.err.find("updated the golden of frog-displaced-screen") == std::string::npos);
  CHECK(test::slurp(golden) != before);
  CHECK(test::run_cli("check " + suite.string() + " -o " + report.string()).exit_code == 0);
  // The environment switch: a new case (its golden removed) is written back.
  fs::remove(dir / "suite/views/frog-pn-factors.png");
  const auto fresh = test::run_cli("check " + suite.string() + " -o " + report.string());
  CHECK(fresh.exit_code == 1);
  CHECK(fresh.err.find("the new cases' images") != std::string::npos);
  CHECK(test::run_cli("check " + suite.string() + " --threads -2").exit_code == 2);
  const int env = std::system(("TESSERA_UPDATE_GOLDEN=1 " + std::string(TESSERA_BIN) + " -q check " + suite.string() +
                               " -o " + report.string() + " >/dev/null 2>&1")
                                  .c_str());
  CHECK(WEXITSTATUS(env) == 0);
  CHECK(fs::exists(dir / "suite/views/frog-pn-factors.png"));
}

TEST_CASE("A suite runs wherever it is copied: --collect-assets, and a missing asset named in one line",
          "[check][cli]") {
  const fs::path dir = test::cli_temp_dir() / "check-move";
  fs::remove_all(dir);
  const fs::path home = dir / "a" / "suite";
  fs::create_directories(home / "scenes");
  const std::string scene = (home / "scenes" / "pyramid.json").string();
  REQUIRE(test::run_cli("-q render " + test::data("osd-shapes/catmark_pyramid.obj") +
                        " --resolution 160x120 --view factors --print-scene " + scene)
              .exit_code == 0);
  std::ofstream(home / "suite.json")
      << R"({"tessera_suite": 1, "name": "moved", "golden": "golden", "cases": [{"name": "pyramid", )"
      << R"("scene": "scenes/pyramid.json", "compare": "exact", "checks": ["watertight"]}]})";
  const std::string suite = (home / "suite.json").string();
  REQUIRE(test::run_cli("-q check --update " + suite + " -o " + (dir / "r0").string()).exit_code == 0);
  // Moved one folder deeper, the scene's relative path to the asset no longer holds: one line names it.
  const fs::path away = dir / "b" / "c" / "suite";
  fs::create_directories(away.parent_path());
  fs::copy(home, away, fs::copy_options::recursive);
  const auto lost = test::run_cli("check " + (away / "suite.json").string() + " -o " + (dir / "r1").string());
  CHECK(lost.exit_code == 1);
  CHECK(lost.err.find("catmark_pyramid.obj does not exist, nor ") != std::string::npos);
  CHECK(lost.err.find("--collect-assets") != std::string::npos);
  // Collected, the suite carries its assets, and runs from anywhere with the same goldens.
  const auto collect = test::run_cli("check " + suite + " --collect-assets");
  INFO(collect.err);
  REQUIRE(collect.exit_code == 0);
  CHECK(fs::exists(home / "assets" / "catmark_pyramid.obj"));
  fs::remove_all(away);
  fs::copy(home, away, fs::copy_options::recursive);
  const auto moved = test::run_cli("check " + (away / "suite.json").string() + " -o " + (dir / "r2").string());
  INFO(moved.err);
  CHECK(moved.exit_code == 0);
  // A suite whose scenes were left as they were, with the assets folder copied beside it, runs too.
  fs::remove_all(away);
  fs::copy(home, away, fs::copy_options::recursive);
  std::ofstream(away / "scenes" / "pyramid.json") << test::run_cli("-q render " + test::data("osd-shapes/catmark_pyramid.obj") +
                                                                 " --resolution 160x120 --view factors --print-scene -").out;
  std::string text;
  {
    std::ifstream in(away / "scenes" / "pyramid.json");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  text = std::regex_replace(text, std::regex(R"("asset": "[^"]*")"), R"("asset": "/nowhere/catmark_pyramid.obj")");
  std::ofstream(away / "scenes" / "pyramid.json") << text;
  CHECK(test::run_cli("check " + (away / "suite.json").string() + " -o " + (dir / "r3").string()).exit_code == 0);
}

TEST_CASE("Shards merge into the single run's report", "[check][cli]") {
  const fs::path dir = test::cli_temp_dir() / "check-shards";
  fs::remove_all(dir);
  const std::string suite = (kSuites / "views.json").string();
  REQUIRE(test::run_cli("check " + suite + " -o " + (dir / "all").string()).exit_code == 0);
  REQUIRE(test::run_cli("check " + suite + " --shard 1/2 -o " + (dir / "s1").string()).exit_code == 0);
  REQUIRE(test::run_cli("check " + suite + " --shard 2/2 -o " + (dir / "s2").string()).exit_code == 0);
  CHECK(summary_of(dir / "s1")["cases"].size() == 3);
  REQUIRE(test::run_cli("check --merge " + (dir / "s2").string() + " " + (dir / "s1").string() + " -o " +
                        (dir / "merged").string())
              .exit_code == 0);
  const auto all = summary_of(dir / "all"), merged = summary_of(dir / "merged");
  REQUIRE(all["cases"].size() == merged["cases"].size());
  for (std::size_t i = 0; i < all["cases"].size(); ++i) {
    CHECK(all["cases"][i]["name"] == merged["cases"][i]["name"]);
    CHECK(all["cases"][i]["status"] == merged["cases"][i]["status"]);
    CHECK(all["cases"][i]["compare"]["hash_new"] == merged["cases"][i]["compare"]["hash_new"]);
    CHECK(test::slurp(dir / "all" / all["cases"][i]["new_image"].get<std::string>()) ==
          test::slurp(dir / "merged" / merged["cases"][i]["new_image"].get<std::string>()));
  }
  // A case in two shards is refused.
  const auto twice = test::run_cli("check --merge " + (dir / "s1").string() + " " + (dir / "s1").string() + " -o " +
                                   (dir / "bad").string());
  CHECK(twice.exit_code == 1);
  CHECK(twice.err.find("in two of the merged reports") != std::string::npos);
}

TEST_CASE("Bad suites: one line naming the file and the field", "[check][cli]") {
  const fs::path dir = test::cli_temp_dir() / "check-bad";
  fs::create_directories(dir);
  const std::pair<const char*, const char*> cases[] = {
      {R"({"tessera_suite": 1, "cases": [{"name": "a", "scene": "s.json", "colour": 1}]})",
       "\"cases[0].colour\": not a case field"},
      {R"({"tessera_suite": 1, "cases": [{"name": "a", "scene": "s.json"}, {"name": "a", "scene": "t.json"}]})",
       "used twice"},
      {R"({"tessera_suite": 1, "cases": [{"name": "a b", "scene": "s.json"}]})", "\"cases[0].name\""},
      {R"({"tessera_suite": 1, "cases": [{"name": "a", "scene": "s.json", "compare": {"fial": 1}}]})",
       "not an idiff threshold"},
      {R"({"tessera_suite": 1, "cases": [{"name": "a", "scene": "s.json", "checks": ["speed"]}]})",
       "is not watertight"},
      {R"({"tessera_suite": 1, "cases": []})", "\"cases\": expected a non-empty list"},
      {R"({"tessera_suite": 2, "cases": []})", "\"tessera_suite\": must be 1"},
      {R"({"tessera_suite": 1,)", "not JSON"}};
  int n = 0;
  for (const auto& [text, message] : cases) {
    const fs::path file = dir / ("bad" + std::to_string(n++) + ".json");
    std::ofstream(file) << text;
    const auto r = test::run_cli("check " + file.string() + " -o " + (dir / "report").string());
    INFO(text);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find(file.string()) != std::string::npos);
    CHECK(r.err.find(message) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  // A case whose scene is missing is an error case (the rest of the suite still runs), exit 1.
  std::ofstream(dir / "missing.json") << R"({"tessera_suite": 1, "cases": [{"name": "a", "scene": "nope.json"}]})";
  const auto r = test::run_cli("check " + (dir / "missing.json").string() + " -o " + (dir / "report").string());
  CHECK(r.exit_code == 1);
  CHECK(summary_of(dir / "report")["cases"][0]["status"] == "error");
  CHECK(test::run_cli("check --shard 3/2 " + (dir / "missing.json").string()).exit_code == 2);
}

TEST_CASE("check: what a scheme leaves out of a case's cage is in its report", "[check][cli]") {
  // A creased cube under pn: the case's warning line reaches summary.json and report.html.
  const fs::path dir = test::cli_temp_dir() / "check-warnings";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "cube.json")
      << R"({"tessera_scene": 1, "asset": ")" +
             (fs::path(TESSERA_TEST_DATA_DIR) / "osd-shapes/catmark_cube_creases1.obj").string() +
             R"(", "scheme": "pn", "resolution": [64, 48]})";
  std::ofstream(dir / "suite.json")
      << R"({"tessera_suite": 1, "name": "warnings", "golden": "golden", "cases": [{"name": "cube-pn", "scene": "cube.json"}]})";
  const fs::path report = dir / "report";
  const auto r = test::run_cli("-q check " + (dir / "suite.json").string() + " -o " + report.string());
  INFO(r.err);
  CHECK(r.exit_code == 1);  // new: no golden yet
  const auto s = summary_of(report);
  const std::string said = "--scheme pn draws the cage's 12 creased edges (12 semi-sharp) smooth";
  REQUIRE(s["cases"][0].contains("warnings"));
  CHECK(s["cases"][0]["warnings"][0].get<std::string>().find(said) != std::string::npos);
  const std::string html = test::slurp(report / "report.html");
  CHECK(html.find("<span class=\"note\">warning: ") != std::string::npos);
  CHECK(html.find("12 creased edges (12 semi-sharp) smooth") != std::string::npos);
}

}  // namespace tessera
