#include "bench_report.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <thread>

#include "text_table.h"

namespace edacrt::cli {
namespace {

double minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

std::vector<double> frame_seconds(const MethodRun& m) {
    std::vector<double> frame(m.prepare_seconds.size());
    for (std::size_t i = 0; i < frame.size(); ++i)
        frame[i] = m.prepare_seconds[i] + m.trace_seconds[i];
    return frame;
}

std::string agreement_text(const MethodRun& m) {
    if (m.reference) return "reference";
    const Agreement& a = m.agreement;
    if (a.disagreements) return "FAIL " + std::to_string(a.disagreements);
    return a.tolerated ? "ok (" + std::to_string(a.tolerated) + " tol)" : "ok";
}

/// Per-ray test counts; Embree does not count.
std::optional<double> per_ray(const MethodRun& m, std::uint64_t tests) {
    if (m.method == Method::embree || m.stats.rays == 0) return std::nullopt;
    return double(tests) / double(m.stats.rays);
}

std::string format(const char* pattern, double value) {
    char text[32];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

std::string optional_text(std::optional<double> value, const char* pattern) {
    return value ? format(pattern, *value) : "n/a";
}

using Column = cli::Column<Row>;

const Column kColumns[] = {
    {"scene", 11, true, [](const Row& r) { return r.run->scene; }},
    {"set", 12, true, [](const Row& r) { return r.run->set; }},
    {"rays", 10, false, [](const Row& r) { return std::to_string(r.run->rays); }},
    {"thr", 4, false, [](const Row& r) { return std::to_string(r.run->threads); }},
    {"method", 14, true, [](const Row& r) { return r.method->label; }},
    {"frame ms", 9, false, [](const Row& r) { return format("%.2f", r.frame_median * 1e3); }},
    {"frame min", 9, false, [](const Row& r) { return format("%.2f", r.frame_min * 1e3); }},
    {"trace ms", 9, false, [](const Row& r) { return format("%.2f", r.trace_median * 1e3); }},
    {"trace min", 9, false, [](const Row& r) { return format("%.2f", r.trace_min * 1e3); }},
    {"prep ms", 9, false, [](const Row& r) { return format("%.2f", r.prepare_median * 1e3); }},
    {"Mrays/s", 8, false, [](const Row& r) { return format("%.2f", r.mrays_frame); }},
    {"(trace)", 8, false, [](const Row& r) { return format("%.2f", r.mrays_trace); }},
    {"x embree", 8, false, [](const Row& r) { return optional_text(r.frame_per_embree, "%.2f"); }},
    {"box/ray", 8, false,
     [](const Row& r) {
         return optional_text(per_ray(*r.method, r.method->stats.ray_box_tests), "%.1f");
     }},
    {"tri/ray", 8, false,
     [](const Row& r) {
         return optional_text(per_ray(*r.method, r.method->stats.ray_triangle_tests), "%.1f");
     }},
    {"MB", 7, false,
     [](const Row& r) { return format("%.1f", double(r.method->working_bytes) * 1e-6); }},
    {"agreement", 12, true, [](const Row& r) { return agreement_text(*r.method); }},
};
const Column kScalingColumn = {"1t/Nt", 6, false,
                               [](const Row& r) { return optional_text(r.scaling, "%.2f"); }};

std::vector<Column> columns(bool sweep) {
    std::vector<Column> all(std::begin(kColumns), std::end(kColumns));
    if (sweep) all.push_back(kScalingColumn);
    return all;
}

std::string cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.starts_with("model name")) {
            const std::size_t colon = line.find(':');
            if (colon != std::string::npos)
                return line.substr(line.find_first_not_of(" \t", colon + 1));
        }
    return "unknown";
}

}  // namespace

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<Row> make_rows(const SetRun& run, const SetRun* single_thread) {
    double best_embree = std::numeric_limits<double>::infinity();
    std::size_t best = run.methods.size();
    for (std::size_t i = 0; i < run.methods.size(); ++i) {
        const double frame = median(frame_seconds(run.methods[i]));
        if (run.methods[i].method == Method::embree && frame < best_embree) {
            best_embree = frame;
            best = i;
        }
    }
    std::vector<Row> rows;
    for (std::size_t i = 0; i < run.methods.size(); ++i) {
        const MethodRun& m = run.methods[i];
        Row row;
        row.run = &run;
        row.method = &m;
        const std::vector<double> frame = frame_seconds(m);
        row.frame_median = median(frame);
        row.frame_min = minimum(frame);
        row.trace_median = median(m.trace_seconds);
        row.trace_min = minimum(m.trace_seconds);
        row.prepare_median = median(m.prepare_seconds);
        row.mrays_frame = double(run.rays) / row.frame_median * 1e-6;
        row.mrays_trace = double(run.rays) / row.trace_median * 1e-6;
        if (best < run.methods.size()) row.frame_per_embree = row.frame_median / best_embree;
        row.shown = m.method != Method::embree || i == best;
        if (single_thread)
            for (const MethodRun& one : single_thread->methods)
                if (one.label == m.label)
                    row.scaling = median(frame_seconds(one)) / row.frame_median;
        rows.push_back(row);
    }
    return rows;
}

std::string table_header(bool sweep) { return text_table_header<Row>(columns(sweep)); }

std::string table_row(const Row& row, bool sweep) {
    return text_table_row<Row>(columns(sweep), row);
}

std::string markdown_table(const std::vector<Row>& rows, bool sweep) {
    return cli::markdown_table<Row>(columns(sweep), rows, [](const Row& r) { return r.shown; });
}

nlohmann::json machine_json() {
    char date[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return {{"cpu", cpu_model()},
            {"hardware_threads", std::thread::hardware_concurrency()},
            {"memory_bytes",
             std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGE_SIZE))},
            {"git_revision", EDACRT_GIT_REVISION},
            {"date", date}};
}

nlohmann::json row_json(const Row& row) {
    const MethodRun& m = *row.method;
    const auto optional = [](std::optional<double> v) -> nlohmann::json {
        return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    const Agreement& a = m.agreement;
    return {{"scene", row.run->scene},
            {"set", row.run->set},
            {"query", enum_name(kQueries, row.run->query)},
            {"rays", row.run->rays},
            {"threads", row.run->threads},
            {"method", m.label},
            {"best_embree_mode", m.method == Method::embree && row.shown},
            {"prepare_seconds", m.prepare_seconds},
            {"trace_seconds", m.trace_seconds},
            {"frame_seconds_median", row.frame_median},
            {"frame_seconds_min", row.frame_min},
            {"trace_seconds_median", row.trace_median},
            {"trace_seconds_min", row.trace_min},
            {"prepare_seconds_median", row.prepare_median},
            {"mrays_per_second_frame", row.mrays_frame},
            {"mrays_per_second_trace", row.mrays_trace},
            {"frame_time_per_best_embree", optional(row.frame_per_embree)},
            {"box_tests_per_ray", optional(per_ray(m, m.stats.ray_box_tests))},
            {"triangle_tests_per_ray", optional(per_ray(m, m.stats.ray_triangle_tests))},
            {"working_bytes", m.working_bytes},
            {"scaling_1_thread_over_n", optional(row.scaling)},
            {"agreement",
             {{"reference", m.reference},
              {"ties", a.ties},
              {"tolerated", a.tolerated},
              {"disagreements", a.disagreements},
              {"first_disagreement", a.first_disagreement}}}};
}

}  // namespace edacrt::cli
