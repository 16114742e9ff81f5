#include "tools/scene/check_report.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "tools/scene/common.h"

namespace tessera::scene {
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

// A metric as a reader wants it: four significant digits (exact integers stay whole); null is "n/a"
// (PSNR of identical images).
std::string rounded(const Json& j) {
  if (j.is_null()) return "n/a";
  if (j.is_number_integer() || j.is_number_unsigned()) return j.dump();
  if (!j.is_number()) return text_of(j);
  return metric_text(j.get<double>());
}

// The page's behaviour, kept small and offline: a wipe slider between new (left) and golden (right), a
// flip button (or the f key over a case) that alternates them in place, and a click on any image
// toggling 1:1 size.
constexpr const char* kReportScript = R"(
function wipe(range){var box=range.parentNode.querySelector('.wipe');
  box.querySelector('.top').style.clipPath='inset(0 '+(100-range.value)+'% 0 0)';}
function flip(button){var box=button.parentNode.querySelector('.wipe');var top=box.querySelector('.top');
  var showing=top.dataset.flipped==='1';top.dataset.flipped=showing?'0':'1';
  top.style.visibility=showing?'visible':'hidden';
  button.textContent=showing?'flip: showing new':'flip: showing golden';}
function zoom(img){img.classList.toggle('full');var box=img.closest('.wipe');if(box)box.classList.toggle('full');}
document.addEventListener('keydown',function(e){if(e.key!=='f')return;
  var hovered=document.querySelector('tr:hover button.flip');if(hovered)flip(hovered);});
)";

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
    << "img{max-width:480px;image-rendering:pixelated;border:1px solid #ccc;background:#fff;cursor:zoom-in}\n"
    << "img.full{max-width:none;cursor:zoom-out}\n"
    << "figure{display:inline-block;margin:0 8px 8px 0;vertical-align:top}figcaption{font-size:12px;color:#555}\n"
    << ".wipe{position:relative;display:inline-block;max-width:480px}.wipe.full{max-width:none}"
       ".wipe img{display:block;max-width:100%}.wipe img.full{max-width:none}"
       ".wipe .top{position:absolute;left:0;top:0}\n"
    << "input[type=range]{width:480px;display:block}\n"
    << "code{font-size:12px;background:#eee;padding:2px 4px;word-break:break-all}\n"
    << ".changes td{border:none;padding:0 8px 0 0;font-size:12px}\n"
    << "</style>\n<script>" << kReportScript
    << "</script></head><body>\n<h1>tessera check: " << escape(text_of(summary["suite"])) << "</h1>\n<p>";
  for (const auto& [status, n] : counts.items())
    if (n.get<int>() > 0)
      h << "<span class=\"s " << escape(status) << "\">" << n.get<int>() << " " << escape(status) << "</span> ";
  h << " &middot; " << summary["cases"].size() << " cases, " << fixed_seconds(summary["seconds"].get<double>())
    << " s &middot; images: drag the slider to wipe between new (left) and golden (right), flip (or press f "
       "over a case) to alternate them, click an image for 1:1, or open it alone from its caption</p>\n"
    << "<table><tr><th>case</th><th>images</th><th>metrics</th></tr>\n";
  for (const Json& c : summary["cases"]) {
    const std::string status = text_of(c["status"]);
    h << "<tr><td><b>" << escape(text_of(c["name"])) << "</b><br><span class=\"s " << escape(status) << "\">"
      << escape(status) << "</span><br>" << escape(text_of(c["message"]));
    if (c.contains("warnings"))
      for (const Json& w : c["warnings"]) h << "<br><span class=\"note\">warning: " << escape(text_of(w)) << "</span>";
    h << "<br><code>" << escape(text_of(c["command"])) << "</code>";
    if (c.contains("scene_changes") && !c["scene_changes"].empty()) {
      h << "<br>scene fields that differ from the golden's:<table class=\"changes\"><tr><td>field</td><td>golden</td>"
           "<td>new</td></tr>";
      for (const Json& d : c["scene_changes"])
        h << "<tr><td>" << escape(text_of(d["field"])) << "</td><td>" << escape(d["golden"].dump()) << "</td><td>"
          << escape(d["new"].dump()) << "</td></tr>";
      h << "</table>";
    }
    h << "</td><td>";
    const std::string golden_rel = "golden/" + text_of(c["name"]) + ".png";
    const std::string new_rel = text_of(c["new_image"]);
    const bool has_golden = c.contains("report_golden") && c["report_golden"].get<bool>();
    const auto caption = [](const std::string& src, const std::string& what) {
      return "<figcaption><a href=\"" + escape(src) + "\" target=\"_blank\">" + what + " (full size)</a></figcaption>";
    };
    if (has_golden) {
      h << "<figure><div class=\"wipe\"><img src=\"" << escape(golden_rel)
        << "\" alt=\"golden\" onclick=\"zoom(this)\">"
        << "<img class=\"top\" src=\"" << escape(new_rel) << "\" alt=\"new\" onclick=\"zoom(this)\"></div>"
        << "<input type=\"range\" min=\"0\" max=\"100\" value=\"50\" oninput=\"wipe(this)\" "
           "aria-label=\"wipe between new and golden\">"
        << "<button class=\"flip\" onclick=\"flip(this)\">flip: showing new</button> " << caption(new_rel, "new")
        << caption(golden_rel, "golden") << "</figure>";
    } else {
      h << "<figure><img src=\"" << escape(new_rel) << "\" alt=\"new\" onclick=\"zoom(this)\">"
        << caption(new_rel, "new") << "</figure>";
    }
    if (!text_of(c["diff_image"]).empty())
      h << "<figure><img src=\"" << escape(text_of(c["diff_image"])) << "\" alt=\"diff\" onclick=\"zoom(this)\">"
        << caption(text_of(c["diff_image"]), "difference") << "</figure>";
    h << "</td><td>";
    if (c.contains("compare")) {
      const Json& m = c["compare"];
      h << "verdict " << escape(text_of(m["verdict"])) << (m["identical"].get<bool>() ? " (identical)" : "")
        << "<br>max error " << rounded(m["max_error"]) << " at " << escape(m["max_pixel"].dump()) << "<br>mean "
        << rounded(m["mean_error"]) << ", RMS " << rounded(m["rms_error"]) << ", PSNR " << rounded(m["psnr"])
        << (m["psnr"].is_null() ? "" : " dB") << "<br>pixels over warn " << rounded(m["over_warn"]) << ", over fail "
        << rounded(m["over_fail"]) << " of " << rounded(m["pixels"]);
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

std::string metric_text(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

}  // namespace tessera::scene
