#include "bench_report.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <map>
#include <string_view>
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

/// Per-ray test counts; Embree does not count.
std::optional<double> per_ray(const MethodRun& m, std::uint64_t tests) {
    if (m.variant.method == Method::embree || m.stats.rays == 0) return std::nullopt;
    return double(tests) / double(m.stats.rays);
}

std::string format(const char* pattern, double value) {
    char text[32];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

std::string optional_text(std::optional<double> value, const char* pattern = "%.2f") {
    return value ? format(pattern, *value) : "n/a";
}

nlohmann::json optional_json(std::optional<double> value) {
    return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

// The cells, each once; the layouts below choose and order them.
std::string scene(const Row& r) { return r.run->scene; }
std::string set(const Row& r) { return r.run->set; }
std::string rays(const Row& r) { return std::to_string(r.run->rays); }
std::string threads(const Row& r) { return std::to_string(r.run->threads); }
std::string rays_per_triangle(const Row& r) { return format("%.3g", r.run->rays_per_triangle()); }
std::string label(const Row& r) { return r.method->variant.label; }
std::string update_work(const Row& r) {
    return std::string(enum_name(kUpdateWorks, r.method->work));
}
std::string frame_ms(const Row& r) { return format("%.2f", r.frame_median * 1e3); }
std::string frame_min_ms(const Row& r) { return format("%.2f", r.frame_min * 1e3); }
std::string trace_ms(const Row& r) { return format("%.2f", r.trace_median * 1e3); }
std::string trace_min_ms(const Row& r) { return format("%.2f", r.trace_min * 1e3); }
std::string prepare_ms(const Row& r) { return format("%.2f", r.prepare_median * 1e3); }
std::string mrays_frame(const Row& r) { return format("%.2f", r.mrays_frame); }
std::string mrays_trace(const Row& r) { return format("%.2f", r.mrays_trace); }
std::string per_embree(const Row& r) { return optional_text(r.frame_per_embree); }
std::string per_edacrt(const Row& r) { return optional_text(r.frame_per_edacrt); }
std::string box_per_ray(const Row& r) {
    return optional_text(per_ray(*r.method, r.method->stats.ray_box_tests), "%.1f");
}
std::string triangle_per_ray(const Row& r) {
    return optional_text(per_ray(*r.method, r.method->stats.ray_triangle_tests), "%.1f");
}
std::string megabytes(const Row& r) {
    return format("%.1f", double(r.method->working_bytes) * 1e-6);
}
std::string agreement(const Row& r) {
    if (r.method->reference) return "reference";
    const Agreement& a = r.method->agreement;
    if (a.disagreements) return "FAIL " + std::to_string(a.disagreements);
    return a.tolerated ? "ok (" + std::to_string(a.tolerated) + " tol)" : "ok";
}
std::string scaling(const Row& r) { return optional_text(r.scaling); }

using Column = cli::Column<Row>;

// Every column once, its width 0; the layouts below choose, order and size them.
const Column kColumns[] = {{"scene", 0, true, scene},
                           {"set", 0, true, set},
                           {"rays", 0, false, rays},
                           {"thr", 0, false, threads},
                           {"rays/tri", 0, false, rays_per_triangle},
                           {"method", 0, true, label},
                           {"update", 0, true, update_work},
                           {"frame ms", 0, false, frame_ms},
                           {"frame min", 0, false, frame_min_ms},
                           {"trace ms", 0, false, trace_ms},
                           {"trace min", 0, false, trace_min_ms},
                           {"prep ms", 0, false, prepare_ms},
                           {"update ms", 0, false, prepare_ms},
                           {"Mrays/s", 0, false, mrays_frame},
                           {"(trace)", 0, false, mrays_trace},
                           {"x embree", 0, false, per_embree},
                           {"x edacrt", 0, false, per_edacrt},
                           {"box/ray", 0, false, box_per_ray},
                           {"tri/ray", 0, false, triangle_per_ray},
                           {"MB", 0, false, megabytes},
                           {"agreement", 0, true, agreement},
                           {"1t/Nt", 0, false, scaling}};

struct Placed {
    std::string_view title;
    int width;  // in the stdout table
};
constexpr Placed kStill[] = {{"scene", 11},    {"set", 12},     {"rays", 10},     {"thr", 4},
                             {"method", 14},   {"frame ms", 9}, {"frame min", 9}, {"trace ms", 9},
                             {"trace min", 9}, {"prep ms", 9},  {"Mrays/s", 8},   {"(trace)", 8},
                             {"x embree", 8},  {"box/ray", 8},  {"tri/ray", 8},   {"MB", 7},
                             {"agreement", 12}};
constexpr Placed kScaling = {"1t/Nt", 6};
constexpr Placed kAnimated[] = {{"scene", 8},     {"set", 12},     {"rays", 9},
                                {"rays/tri", 8},  {"method", 14},  {"update", 8},
                                {"update ms", 9}, {"trace ms", 9}, {"frame ms", 9},
                                {"frame min", 9}, {"x edacrt", 8}, {"agreement", 10}};

std::vector<Column> columns(TableLayout layout) {
    std::vector<Placed> placed;
    if (layout.animated)
        placed.assign(std::begin(kAnimated), std::end(kAnimated));
    else
        placed.assign(std::begin(kStill), std::end(kStill));
    if (layout.thread_sweep && !layout.animated) placed.push_back(kScaling);
    std::vector<Column> out;
    for (const Placed& p : placed) {
        Column c = *std::find_if(std::begin(kColumns), std::end(kColumns),
                                 [&](const Column& column) { return column.title == p.title; });
        c.width = p.width;
        out.push_back(c);
    }
    return out;
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
    // Still, the Embree modes are one method: the fastest is shown and is the ratios' base.
    double best_embree = std::numeric_limits<double>::infinity();
    std::size_t best = run.methods.size();
    std::optional<double> edacrt;
    for (std::size_t i = 0; i < run.methods.size(); ++i) {
        const MethodRun& m = run.methods[i];
        const double frame = median(frame_seconds(m));
        if (!run.animated && m.variant.method == Method::embree && frame < best_embree) {
            best_embree = frame;
            best = i;
        }
        if (m.variant.label == "edacrt") edacrt = frame;
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
        if (edacrt) row.frame_per_edacrt = row.frame_median / *edacrt;
        row.shown = run.animated || m.variant.method != Method::embree || i == best;
        if (single_thread)
            for (const MethodRun& one : single_thread->methods)
                if (one.variant.label == m.variant.label)
                    row.scaling = median(frame_seconds(one)) / row.frame_median;
        rows.push_back(row);
    }
    return rows;
}

std::string table_header(TableLayout layout) { return text_table_header<Row>(columns(layout)); }

std::string table_row(const Row& row, TableLayout layout) {
    return text_table_row<Row>(columns(layout), row);
}

std::string markdown_table(const std::vector<Row>& rows, TableLayout layout) {
    return cli::markdown_table<Row>(columns(layout), rows,
                                    [](const Row& r) { return r.shown && !r.run->sweep(); });
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
    const SetRun& run = *row.run;
    const MethodRun& m = *row.method;
    const Agreement& a = m.agreement;
    nlohmann::json json = {{"scene", run.scene},
                           {"set", run.set},
                           {"rays", run.rays},
                           {"method", m.variant.label},
                           {"trace_seconds", m.trace_seconds},
                           {"frame_seconds_median", row.frame_median},
                           {"frame_seconds_min", row.frame_min},
                           {"trace_seconds_median", row.trace_median},
                           {"agreement",
                            {{"reference", m.reference},
                             {"ties", a.ties},
                             {"tolerated", a.tolerated},
                             {"disagreements", a.disagreements},
                             {"first_disagreement", a.first_disagreement}}}};
    if (run.animated) {
        json.update({{"spp", run.spp},
                     {"triangles", run.triangles},
                     {"rays_per_triangle", run.rays_per_triangle()},
                     {"update_mode", enum_name(kSceneUpdates, m.variant.how)},
                     {"update_work", enum_name(kUpdateWorks, m.work)},
                     {"animate_seconds", run.animate_seconds},
                     {"update_seconds", m.prepare_seconds},
                     {"update_seconds_median", row.prepare_median},
                     {"frame_time_per_edacrt", optional_json(row.frame_per_edacrt)}});
        return json;
    }
    json.update({{"query", enum_name(kQueries, run.query)},
                 {"threads", run.threads},
                 {"best_embree_mode", m.variant.method == Method::embree && row.shown},
                 {"prepare_seconds", m.prepare_seconds},
                 {"trace_seconds_min", row.trace_min},
                 {"prepare_seconds_median", row.prepare_median},
                 {"mrays_per_second_frame", row.mrays_frame},
                 {"mrays_per_second_trace", row.mrays_trace},
                 {"frame_time_per_best_embree", optional_json(row.frame_per_embree)},
                 {"box_tests_per_ray", optional_json(per_ray(m, m.stats.ray_box_tests))},
                 {"triangle_tests_per_ray", optional_json(per_ray(m, m.stats.ray_triangle_tests))},
                 {"working_bytes", m.working_bytes},
                 {"scaling_1_thread_over_n", optional_json(row.scaling)}});
    return json;
}

std::vector<Crossover> crossovers(const std::vector<SetRun>& runs) {
    // Per scene and method: (rays per triangle, frame time / EDACRT's), ascending.
    std::map<std::pair<std::string, std::string>, std::vector<std::pair<double, double>>> curves;
    for (const SetRun& run : runs) {
        if (!run.sweep()) continue;
        for (const Row& row : make_rows(run)) {
            const Method method = row.method->variant.method;
            if (!row.frame_per_edacrt || method == Method::edacrt || method == Method::dacrt)
                continue;
            curves[{run.scene, row.method->variant.label}].emplace_back(run.rays_per_triangle(),
                                                                        *row.frame_per_edacrt);
        }
    }
    std::vector<Crossover> out;
    for (auto& [key, points] : curves) {
        std::sort(points.begin(), points.end());
        // From the last point where the method was slower, it is faster at every larger one.
        std::size_t first_fast = points.size();
        while (first_fast > 0 && points[first_fast - 1].second < 1.0) --first_fast;
        Crossover c{key.first, key.second, std::nullopt, {}};
        if (first_fast == points.size()) {
            c.text = "above " + format("%.3g", points.back().first);
        } else if (first_fast == 0) {
            c.text = "below " + format("%.3g", points.front().first);
        } else {
            const auto [r0, q0] = points[first_fast - 1];
            const auto [r1, q1] = points[first_fast];
            const double f0 = std::log(q0), f1 = std::log(q1);  // f0 >= 0 > f1
            const double at =
                std::exp(std::log(r0) + f0 / (f0 - f1) * (std::log(r1) - std::log(r0)));
            c.rays_per_triangle = at;
            c.text = format("%.3g", at);
        }
        out.push_back(c);
    }
    return out;
}

std::string crossover_markdown_table(const std::vector<Crossover>& crossovers) {
    std::string text =
        "| scene | method | faster than edacrt from (rays per triangle) |\n"
        "|---|---|---:|\n";
    for (const Crossover& c : crossovers)
        text += "| " + c.scene + " | " + c.method + " | " + c.text + " |\n";
    return text;
}

nlohmann::json crossover_json(const Crossover& c) {
    return {{"scene", c.scene},
            {"method", c.method},
            {"rays_per_triangle", optional_json(c.rays_per_triangle)},
            {"text", c.text}};
}

}  // namespace edacrt::cli
