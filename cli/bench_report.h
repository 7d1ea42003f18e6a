#pragma once
// The measurements of `edacrt bench`, still or animated (--dynamic), and their three forms: a
// table on stdout, JSON, markdown; for animated scenes also the crossover: the rays per
// triangle from which a structure updated every frame pays for itself against EDACRT, which
// keeps none.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "trace/edacrt_params.h"
#include "trace/hit_agreement.h"
#include "trace/tracer.h"

namespace edacrt::cli {

/// A tracer to time: a method, how it is made and how it takes each animated frame.
struct Variant {
    std::string label;  // "edacrt", "embree/packet8", "bvh/refit", "edacrt/presplit-0"
    Method method = Method::edacrt;
    EmbreeMode mode = kDefaultEmbreeMode;
    SceneUpdate how = SceneUpdate::rebuild;  // still frames: always a new tracer, set_scene()
    EdacrtParams params = {};
    BvhBuildOptions bvh = {};
};

/// One variant over the frames of one ray set at one thread count.
struct MethodRun {
    Variant variant;
    UpdateWork work = UpdateWork::none;  // what its updates did, every frame
    // One per frame: set_scene() (still) or update_scene() (animated), and trace().
    std::vector<double> prepare_seconds, trace_seconds;
    TraceStats stats;               // summed over the frames (per ray: their mean)
    std::size_t working_bytes = 0;  // the most of any frame
    Agreement agreement;            // against the reference variant, summed over frames
    bool reference = false;
};

struct SetRun {
    std::string scene, set;  // set: "camera-4spp", "diffuse", ..., or "sweep" (animated)
    Query query = Query::closest;
    std::size_t rays = 0, triangles = 0;
    int threads = 0, spp = 1;
    bool animated = false;
    std::vector<double> animate_seconds;  // animated: one per frame, Animation::frame()
    std::vector<MethodRun> methods;

    double rays_per_triangle() const { return double(rays) / double(triangles); }
    bool sweep() const { return set == "sweep"; }
};

/// What the reports show of a MethodRun. Times are medians (and minima) over its frames; a
/// frame is set_scene() or update_scene() (prepare), then trace().
struct Row {
    const SetRun* run;
    const MethodRun* method;
    double frame_median, frame_min, trace_median, trace_min, prepare_median;
    double mrays_frame, mrays_trace;         // rays per median frame / median trace
    std::optional<double> frame_per_embree;  // still: frame time / the fastest Embree mode's
    std::optional<double> frame_per_edacrt;  // frame time / EDACRT's on the same set
    std::optional<double> scaling;           // frame time at 1 thread / at run->threads
    bool shown = true;                       // false for the slower Embree modes (still)
};

/// The median of `v` (not empty).
double median(std::vector<double> v);

/// Rows of `run`; `single_thread` is the same set at 1 thread (thread sweep), if any.
std::vector<Row> make_rows(const SetRun& run, const SetRun* single_thread = nullptr);

/// The columns of the tables: the still benchmark's (with time(1 thread) / time(N) on a thread
/// sweep) or the animated one's.
struct TableLayout {
    bool animated = false;
    bool thread_sweep = false;
};

std::string table_header(TableLayout layout);
std::string table_row(const Row& row, TableLayout layout);
/// The shown rows of the camera sets (not those of the animated sweep).
std::string markdown_table(const std::vector<Row>& rows, TableLayout layout);
nlohmann::json row_json(const Row& row);

/// CPU model (/proc/cpuinfo), hardware threads, memory, the git revision at configure time and
/// the date (UTC).
nlohmann::json machine_json();

/// Where a method's frame time falls below EDACRT's for good on a scene's sweep.
struct Crossover {
    std::string scene, method;
    std::optional<double> rays_per_triangle;  // interpolated (log-log) between sweep points
    std::string text;  // "3.1", "below 0.0625" (faster everywhere), "above 16" (never)
};

/// For every method of the sweeps of `runs` that keeps a structure (not EDACRT in any of its
/// settings, not DACRT): the smallest rays per triangle from which it is faster than EDACRT at
/// every larger sweep point, interpolated linearly in log(rays per triangle) and log(time
/// ratio) from the last point where it was slower. Empty without EDACRT.
std::vector<Crossover> crossovers(const std::vector<SetRun>& runs);

std::string crossover_markdown_table(const std::vector<Crossover>& crossovers);
nlohmann::json crossover_json(const Crossover& crossover);

}  // namespace edacrt::cli
