#pragma once
// The measurements of `edacrt bench` and their three forms: a table on stdout, JSON, markdown.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "trace/hit_agreement.h"
#include "trace/tracer.h"

namespace edacrt::cli {

/// One method (each Embree mode apart) on one ray set at one thread count.
struct MethodRun {
    std::string label;  // "edacrt", "embree/packet8"
    Method method = Method::edacrt;
    std::vector<double> prepare_seconds, trace_seconds;  // one per repetition
    TraceStats stats;                                    // the same in every repetition
    std::size_t working_bytes = 0;                       // the most of any repetition
    Agreement agreement;                                 // against the reference method
    bool reference = false;
};

struct SetRun {
    std::string scene, set;
    Query query;
    std::size_t rays = 0;
    int threads = 0;
    std::vector<MethodRun> methods;
};

/// What the reports show of a MethodRun. Times are medians (and minima) over repetitions; a
/// frame is set_scene() + trace().
struct Row {
    const SetRun* run;
    const MethodRun* method;
    double frame_median, frame_min, trace_median, trace_min, prepare_median;
    double mrays_frame, mrays_trace;         // rays per median frame / median trace
    std::optional<double> frame_per_embree;  // frame time / the fastest Embree mode's
    std::optional<double> scaling;           // frame time at 1 thread / at run->threads
    bool shown = true;                       // false for the slower Embree modes
};

/// The median of `v` (not empty).
double median(std::vector<double> v);

/// Rows of `run`; `single_thread` is the same set at 1 thread (thread sweep), if any.
std::vector<Row> make_rows(const SetRun& run, const SetRun* single_thread);

std::string table_header(bool sweep);
std::string table_row(const Row& row, bool sweep);
std::string markdown_table(const std::vector<Row>& rows, bool sweep);

/// CPU model (/proc/cpuinfo), hardware threads, memory, the git revision at configure time and
/// the date (UTC).
nlohmann::json machine_json();
nlohmann::json row_json(const Row& row);

}  // namespace edacrt::cli
