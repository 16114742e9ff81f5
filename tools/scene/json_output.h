// The one JSON path of the `tessera` commands: results are built as nlohmann-json values and
// written by json_text, in one style for every command but `analyze` (whose long report prints
// indented, nlohmann's dump(2), as it always has): one line, `{"key": value, "list": [1, 2]}`,
// keys in insertion order, strings escaped by nlohmann, numbers in their shortest round-trip text
// (std::to_chars: 7, 0.25, 2.9604483920546154; NaN and infinities as null).
//
// Json holds doubles. FloatJson holds float32 numbers and prints each as the shortest text that
// reads back to the identical float (pattern --json: tests parse the points back bit for bit).
#pragma once

#include <nlohmann/json.hpp>

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>

#include "pipeline/statistics.h"
#include "tools/verify/weld_check.h"

namespace tessera::scene {

using Json = nlohmann::ordered_json;
using FloatJson =
    nlohmann::basic_json<nlohmann::ordered_map, std::vector, std::string, bool, std::int64_t, std::uint64_t, float>;

// A float as the double nearest its shortest text (float_text), so that JSON shows 3.3 rather
// than 3.299999952316284; either reads back to the same float.
double json_float(float x);
// [x, y, z], each json_float.
Json json_vec3(glm::vec3 v);

// `value` as one line of JSON text (no trailing newline).
std::string json_text(const Json& value);
std::string json_text(const FloatJson& value);

// The pipeline's reports, with the key names of D3D11's pipeline statistics and the stage times in
// seconds ("<stage>_s", thread-seconds except wall_s).
Json to_json(const PipelineStatistics& s);
Json to_json(const StageTimes& t);
Json to_json(const MemoryStats& m);
Json to_json(const verify::WeldReport& w);

}  // namespace tessera::scene
