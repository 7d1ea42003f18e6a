#pragma once
// The measurements of `edacrt bench --dynamic` and their forms (a table on stdout, markdown,
// JSON), and the crossover: the rays per triangle from which a structure updated every frame
// pays for itself against EDACRT, which keeps none.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "trace/hit_agreement.h"
#include "trace/tracer.h"

namespace edacrt::cli {

/// One tracing method with one way of taking each frame, over the frames of one ray set.
struct DynamicMethodRun {
    std::string label;  // "edacrt", "bvh/refit", "embree/dynamic"
    Method method = Method::edacrt;
    SceneUpdate how = SceneUpdate::rebuild;
    UpdateWork work = UpdateWork::none;                 // what its updates did, every frame
    std::vector<double> update_seconds, trace_seconds;  // one per frame
    Agreement agreement;  // summed over the frames, against the reference method
    bool reference = false;
};

struct DynamicSetRun {
    std::string scene, set;  // set: "camera-4spp", or "sweep" for the rays-per-triangle sweep
    std::size_t rays = 0, triangles = 0;
    int spp = 1;
    std::vector<double> animate_seconds;  // one per frame: Animation::frame()
    std::vector<DynamicMethodRun> methods;

    double rays_per_triangle() const { return double(rays) / double(triangles); }
    bool sweep() const { return set == "sweep"; }
};

/// Medians over the frames; a frame is update_scene() + trace().
struct DynamicRow {
    const DynamicSetRun* run;
    const DynamicMethodRun* method;
    double update, trace, frame, frame_min;
    std::optional<double> per_edacrt;  // frame time / EDACRT's on the same set
};

std::vector<DynamicRow> dynamic_rows(const DynamicSetRun& run);

std::string dynamic_table_header();
std::string dynamic_table_row(const DynamicRow& row);
std::string dynamic_markdown_table(const std::vector<DynamicRow>& rows);
nlohmann::json dynamic_row_json(const DynamicRow& row);

/// Where a method's frame time falls below EDACRT's for good on a scene's sweep.
struct Crossover {
    std::string scene, method;
    std::optional<double> rays_per_triangle;  // interpolated (log-log) between sweep points
    std::string text;  // "3.1", "below 0.0625" (faster everywhere), "above 16" (never)
};

/// For every method of the sweeps of `runs` that keeps a structure (not EDACRT in any of its
/// settings, not DACRT): the smallest rays
/// per triangle from which it is faster than EDACRT at every larger sweep point, interpolated
/// linearly in log(rays per triangle) and log(time ratio) from the last point where it was
/// slower. Empty without EDACRT.
std::vector<Crossover> crossovers(const std::vector<DynamicSetRun>& runs);

std::string crossover_markdown_table(const std::vector<Crossover>& crossovers);
nlohmann::json crossover_json(const Crossover& crossover);

}  // namespace edacrt::cli
