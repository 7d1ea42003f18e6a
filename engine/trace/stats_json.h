#pragma once
// A detailed trace's statistics as JSON: `edacrt trace --stats`, `render --stats` and the
// viewer's write-analysis.
#include <nlohmann/json.hpp>
#include <string>

#include "trace/trace_stats.h"

namespace edacrt {

/// Per-level table and per-ray summary (mean and max) of a detailed trace, for --stats.
nlohmann::json stats_json(const TraceDetail& detail);

/// Pretty JSON text with a final newline. Names from files need not be UTF-8 (a Latin-1 MTL):
/// such bytes become U+FFFD instead of failing the dump.
std::string json_text(const nlohmann::json& json);

}  // namespace edacrt
