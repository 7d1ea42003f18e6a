#include "dynamic_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "bench_report.h"
#include "text_table.h"

namespace edacrt::cli {
namespace {

std::string format(const char* pattern, double value) {
    char text[32];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

std::string agreement_text(const DynamicMethodRun& m) {
    if (m.reference) return "reference";
    const Agreement& a = m.agreement;
    if (a.disagreements) return "FAIL " + std::to_string(a.disagreements);
    return a.tolerated ? "ok (" + std::to_string(a.tolerated) + " tol)" : "ok";
}

using Column = cli::Column<DynamicRow>;

const Column kColumns[] = {
    {"scene", 8, true, [](const DynamicRow& r) { return r.run->scene; }},
    {"set", 12, true, [](const DynamicRow& r) { return r.run->set; }},
    {"rays", 9, false, [](const DynamicRow& r) { return std::to_string(r.run->rays); }},
    {"rays/tri", 8, false,
     [](const DynamicRow& r) { return format("%.3g", r.run->rays_per_triangle()); }},
    {"method", 14, true, [](const DynamicRow& r) { return r.method->label; }},
    {"update", 8, true,
     [](const DynamicRow& r) { return std::string(enum_name(kUpdateWorks, r.method->work)); }},
    {"update ms", 9, false, [](const DynamicRow& r) { return format("%.2f", r.update * 1e3); }},
    {"trace ms", 9, false, [](const DynamicRow& r) { return format("%.2f", r.trace * 1e3); }},
    {"frame ms", 9, false, [](const DynamicRow& r) { return format("%.2f", r.frame * 1e3); }},
    {"frame min", 9, false, [](const DynamicRow& r) { return format("%.2f", r.frame_min * 1e3); }},
    {"x edacrt", 8, false,
     [](const DynamicRow& r) {
         return r.per_edacrt ? format("%.2f", *r.per_edacrt) : std::string("n/a");
     }},
    {"agreement", 10, true, [](const DynamicRow& r) { return agreement_text(*r.method); }},
};

std::vector<double> frame_seconds(const DynamicMethodRun& m) {
    std::vector<double> frame(m.update_seconds.size());
    for (std::size_t i = 0; i < frame.size(); ++i)
        frame[i] = m.update_seconds[i] + m.trace_seconds[i];
    return frame;
}

}  // namespace

std::vector<DynamicRow> dynamic_rows(const DynamicSetRun& run) {
    std::optional<double> edacrt;
    for (const DynamicMethodRun& m : run.methods)
        if (m.label == "edacrt") edacrt = median(frame_seconds(m));
    std::vector<DynamicRow> rows;
    for (const DynamicMethodRun& m : run.methods) {
        const std::vector<double> frame = frame_seconds(m);
        DynamicRow row{&run,
                       &m,
                       median(m.update_seconds),
                       median(m.trace_seconds),
                       median(frame),
                       *std::min_element(frame.begin(), frame.end()),
                       std::nullopt};
        if (edacrt) row.per_edacrt = row.frame / *edacrt;
        rows.push_back(row);
    }
    return rows;
}

std::string dynamic_table_header() { return text_table_header<DynamicRow>(kColumns); }

std::string dynamic_table_row(const DynamicRow& row) {
    return text_table_row<DynamicRow>(kColumns, row);
}

std::string dynamic_markdown_table(const std::vector<DynamicRow>& rows) {
    return markdown_table<DynamicRow>(kColumns, rows, [](const DynamicRow&) { return true; });
}

nlohmann::json dynamic_row_json(const DynamicRow& row) {
    const DynamicMethodRun& m = *row.method;
    const Agreement& a = m.agreement;
    return {{"scene", row.run->scene},
            {"set", row.run->set},
            {"spp", row.run->spp},
            {"rays", row.run->rays},
            {"triangles", row.run->triangles},
            {"rays_per_triangle", row.run->rays_per_triangle()},
            {"method", m.label},
            {"update_mode", enum_name(kSceneUpdates, m.how)},
            {"update_work", enum_name(kUpdateWorks, m.work)},
            {"animate_seconds", row.run->animate_seconds},
            {"update_seconds", m.update_seconds},
            {"trace_seconds", m.trace_seconds},
            {"update_seconds_median", row.update},
            {"trace_seconds_median", row.trace},
            {"frame_seconds_median", row.frame},
            {"frame_seconds_min", row.frame_min},
            {"frame_time_per_edacrt",
             row.per_edacrt ? nlohmann::json(*row.per_edacrt) : nlohmann::json(nullptr)},
            {"agreement",
             {{"reference", m.reference},
              {"ties", a.ties},
              {"tolerated", a.tolerated},
              {"disagreements", a.disagreements},
              {"first_disagreement", a.first_disagreement}}}};
}

std::vector<Crossover> crossovers(const std::vector<DynamicSetRun>& runs) {
    // Per scene and method: (rays per triangle, frame time / EDACRT's), ascending.
    std::map<std::pair<std::string, std::string>, std::vector<std::pair<double, double>>> curves;
    for (const DynamicSetRun& run : runs) {
        if (!run.sweep()) continue;
        for (const DynamicRow& row : dynamic_rows(run)) {
            const Method method = row.method->method;
            if (!row.per_edacrt || method == Method::edacrt || method == Method::dacrt) continue;
            curves[{run.scene, row.method->label}].emplace_back(run.rays_per_triangle(),
                                                                *row.per_edacrt);
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
            {"rays_per_triangle",
             c.rays_per_triangle ? nlohmann::json(*c.rays_per_triangle) : nlohmann::json(nullptr)},
            {"text", c.text}};
}

}  // namespace edacrt::cli
