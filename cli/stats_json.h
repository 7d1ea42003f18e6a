#pragma once
#include <nlohmann/json.hpp>

#include "trace/trace_stats.h"

namespace edacrt::cli {

/// Per-level table and per-ray summary (mean and max) of a detailed trace, for --stats.
nlohmann::json to_json(const TraceDetail& detail);

}  // namespace edacrt::cli
