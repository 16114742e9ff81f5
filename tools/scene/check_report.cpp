#include "tools/scene/check_report.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "tools/scene/common.h"

namespace tessera::cli {
namespace {

namespace fs = std::filesystem;

std::string escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string fixed_seconds(double s) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f", s);
  return b;
}

std::string text_of(const Json& j) { return j.is_string() ? j.get<std::string>() : j.dump(); }

std::string html(const Json& summary) {
  std::ostringstream h;
  const Json& counts = summary["counts"];
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>tessera check: "
    << escape(text_of(summary["suite"])) << "</title>\n<style>\n"
    << "body{font:14px/1.4 sans-serif;margin:24px;color:#222;background:#fafafa}\n"
    << "table{border-collapse:collapse;width:100%}td,th{border-bottom:1px solid #ddd;padding:8px;vertical-align:top;"
       "text-align:left}\n"
    << ".s{font-weight:bold;padding:2px 8px;border-radius:4px;color:#fff}.pass{background:#2e7d32}"
       ".warning{background:#b26a00}.note{color:#8a5300}.fail,.error{background:#c62828}.new{background:#1565c0}\n"
    << "img{max-width:320px;image-rendering:pixelated;border:1px solid #ccc;background:#fff}\n"
    << "figure{display:inline-block;margin:0 8px 0 0}figcaption{font-size:12px;color:#555}\n"
    << "code{font-size:12px;background:#eee;padding:2px 4px;word-break:break-all}\n"
    << "</style>\n<script>\n"
    << "// Hovering a new image shows the golden in its place.\n"
    << "function swap(img, on){var g=img.getAttribute('data-golden'); if(!g) return;"
       " if(on){img.dataset.own=img.src; img.src=g;} else if(img.dataset.own){img.src=img.dataset.own;}}\n"
    << "</script></head><body>\n<h1>tessera check: " << escape(text_of(summary["suite"])) << "</h1>\n<p>";
  for (const auto& [status, n] : counts.items())
    if (n.get<int>() > 0)
      h << "<span class=\"s " << escape(status) << "\">" << n.get<int>() << " " << escape(status) << "</span> ";
  h << " &middot; " << summary["cases"].size() << " cases, " << fixed_seconds(summary["seconds"].get<double>())
    << " s</p>\n<table><tr><th>case</th><th>images (hover new: golden)</th><th>metrics</th></tr>\n";
  for (const Json& c : summary["cases"]) {
    const std::string status = text_of(c["status"]);
    h << "<tr><td><b>" << escape(text_of(c["name"])) << "</b><br><span class=\"s " << escape(status) << "\">"
      << escape(status) << "</span><br>" << escape(text_of(c["message"]));
    if (c.contains("warnings"))
      for (const Json& w : c["warnings"]) h << "<br><span class=\"note\">warning: " << escape(text_of(w)) << "</span>";
    h << "<br><code>" << escape(text_of(c["command"])) << "</code></td><td>";
    const std::string golden_rel = "golden/" + text_of(c["name"]) + ".png";
    const bool has_golden = c.contains("report_golden") && c["report_golden"].get<bool>();
    h << "<figure><img src=\"" << escape(text_of(c["new_image"])) << "\" alt=\"new\""
      << (has_golden
              ? " data-golden=\"" + escape(golden_rel) + "\" onmouseover=\"swap(this,1)\" onmouseout=\"swap(this,0)\""
              : "")
      << "><figcaption>new</figcaption></figure>";
    if (has_golden)
      h << "<figure><img src=\"" << escape(golden_rel) << "\" alt=\"golden\"><figcaption>golden</figcaption></figure>";
    if (!text_of(c["diff_image"]).empty())
      h << "<figure><img src=\"" << escape(text_of(c["diff_image"]))
        << "\" alt=\"diff\"><figcaption>difference</figcaption></figure>";
    h << "</td><td>";
    if (c.contains("compare")) {
      const Json& m = c["compare"];
      h << "verdict " << escape(text_of(m["verdict"])) << (m["identical"].get<bool>() ? " (identical)" : "")
        << "<br>max error " << escape(text_of(m["max_error"])) << " at " << escape(m["max_pixel"].dump()) << "<br>mean "
        << escape(text_of(m["mean_error"])) << ", RMS " << escape(text_of(m["rms_error"])) << ", PSNR "
        << escape(text_of(m["psnr"])) << "<br>pixels over warn " << escape(text_of(m["over_warn"])) << ", over fail "
        << escape(text_of(m["over_fail"])) << " of " << escape(text_of(m["pixels"]));
    }
    for (const auto& [key, v] : c["checks"].items())
      h << "<br>" << escape(key) << ": " << escape(text_of(v["new"])) << (v["pass"].get<bool>() ? " = " : " &ne; ")
        << "golden " << escape(text_of(v["golden"]));
    h << "<br>" << fixed_seconds(c["seconds"].get<double>()) << " s</td></tr>\n";
  }
  h << "</table>\n</body></html>\n";
  return h.str();
}

std::string junit(const Json& summary) {
  std::ostringstream x;
  const Json& counts = summary["counts"];
  const int failures = counts["fail"].get<int>() + counts["new"].get<int>();
  const int errors = counts["error"].get<int>();
  const std::string suite = escape(text_of(summary["suite"]));
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"tessera check\" tests=\""
    << summary["cases"].size() << "\" failures=\"" << failures << "\" errors=\"" << errors << "\" time=\""
    << fixed_seconds(summary["seconds"].get<double>()) << "\">\n  <testsuite name=\"" << suite << "\" tests=\""
    << summary["cases"].size() << "\" failures=\"" << failures << "\" errors=\"" << errors << "\" time=\""
    << fixed_seconds(summary["seconds"].get<double>()) << "\">\n";
  for (const Json& c : summary["cases"]) {
    const std::string status = text_of(c["status"]);
    x << "    <testcase classname=\"" << suite << "\" name=\"" << escape(text_of(c["name"])) << "\" time=\""
      << fixed_seconds(c["seconds"].get<double>()) << "\"";
    if (status == "pass" || status == "warning") {
      x << (status == "warning"
                ? ">\n      <system-out>warning: " + escape(text_of(c["message"])) + "</system-out>\n    </testcase>\n"
                : "/>\n");
    } else {
      const char* tag = status == "error" ? "error" : "failure";
      x << ">\n      <" << tag << " message=\"" << escape(status + ": " + text_of(c["message"])) << "\">"
        << escape(text_of(c["command"])) << "</" << tag << ">\n    </testcase>\n";
    }
  }
  x << "  </testsuite>\n</testsuites>\n";
  return x.str();
}

}  // namespace

Json count_statuses(const Json& cases) {
  Json counts = {{"pass", 0}, {"warning", 0}, {"fail", 0}, {"new", 0}, {"error", 0}};
  for (const Json& c : cases) counts[text_of(c["status"])] = counts[text_of(c["status"])].get<int>() + 1;
  return counts;
}

void write_check_reports(const Json& summary, const std::string& dir) {
  fs::create_directories(dir);
  write_text_atomically((fs::path(dir) / "report.html").string(), html(summary));
  write_text_atomically((fs::path(dir) / "junit.xml").string(), junit(summary));
  write_text_atomically((fs::path(dir) / "summary.json").string(), summary.dump(2) + "\n");
}

}  // namespace tessera::cli
