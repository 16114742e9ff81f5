// The reports of `tessera check`, written from the cases' JSON (CaseResult::json(), plus "index", the
// case's place in the suite) so that shards merged later give the same files: report.html (new
// and golden under a wipe slider and a flip button, the heat map beside them, every image at full size
// on a click or its own page, metrics to four digits, the reproducing command, the scene fields that
// differ from the golden's), junit.xml for CI systems, and summary.json.
#pragma once

#include <string>

#include "tools/scene/json_output.h"

namespace tessera::scene {

// `summary`: {"suite", "suite_path", "cases": [...], "counts": {...}, "seconds"}; writes the three files
// into `dir` (atomically, each).
void write_check_reports(const Json& summary, const std::string& dir);

// A metric as the reports and messages give it: four significant digits ("0.001943").
std::string metric_text(double v);

// Counts of each status in `cases`.
Json count_statuses(const Json& cases);

}  // namespace tessera::scene
