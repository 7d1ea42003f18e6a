// Google Benchmark of the tracers on camera rays and on the first diffuse bounce (rays spawned
// from the camera hits), closest and any hit, on the scenes of the list "trace_benchmark" of
// assets/scenes.json: bundled ones always, the others from $EDACRT_SCENES (default
// ../shared/scenes) when present.
//   build/edacrt_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "render/bsdf.h"
#include "render/shading_scene.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "scene/scene_manifest.h"
#include "scene/scene_paths.h"
#include "trace/tracer.h"
#include "util/hash_random.h"

namespace edacrt {
namespace {

struct Workload {
    Scene scene;
    std::vector<Ray> camera;  // 512 x 512 pixel-centre rays
    std::vector<Ray> bounce;  // one cosine-distributed ray from every camera hit
};

const Workload& workload(const std::string& path) {
    static std::map<std::string, std::unique_ptr<Workload>> cache;
    auto& entry = cache[path];
    if (entry) return *entry;
    entry = std::make_unique<Workload>();
    Workload& w = *entry;
    w.scene = load_scene(path);
    const Camera camera = w.scene.camera.value_or(frame_box(w.scene.bounds()));
    w.camera = PinholeProjection(camera, 512, 512).pixel_centre_rays();
    const auto tracer = make_tracer(Method::bvh);
    tracer->set_scene(w.scene);
    std::vector<Hit> hits(w.camera.size());
    tracer->trace(w.camera, hits, Query::closest);
    for (std::size_t i = 0; i < hits.size(); ++i) {
        if (!hits[i].hit()) continue;
        const Surface s = make_surface(w.scene, w.camera[i], hits[i]);
        const std::uint32_t h = pcg_hash(std::uint32_t(i));
        w.bounce.push_back(
            spawn_ray(s, sample_cosine_hemisphere(
                             s.ng, {hash_to_unit_float(h), hash_to_unit_float(pcg_hash(h))})));
    }
    return w;
}

void trace_rays(benchmark::State& state, const std::string& path, Method method, bool bounce,
                Query query) {
    if (!std::filesystem::exists(path)) {
        state.SkipWithError(("scene not found: " + path).c_str());
        return;
    }
    const Workload& w = workload(path);
    const std::vector<Ray>& rays = bounce ? w.bounce : w.camera;
    const auto tracer = make_tracer(method);
    tracer->set_scene(w.scene);
    std::vector<Hit> hits(rays.size());
    for (auto _ : state) {
        tracer->trace(rays, hits, query);
        benchmark::DoNotOptimize(hits.data());
    }
    state.counters["Mrays/s"] = benchmark::Counter(
        double(rays.size()) * 1e-6 * double(state.iterations()), benchmark::Counter::kIsRate);
}

void register_all() {
    const std::filesystem::path source = EDACRT_SOURCE_DIR;
    const SceneManifest manifest = read_scene_manifest(scene_manifest_path(source));
    for (const std::string& name : manifest.list("trace_benchmark")) {
        const std::string path =
            scene_file(*manifest.find(name), source / "assets", default_scenes_dir(source));
        for (Method method : {Method::edacrt, Method::dacrt, Method::bvh, Method::embree})
            for (bool bounce : {false, true})
                for (Query query : {Query::closest, Query::any}) {
                    const std::string label = name + "/" +
                                              std::string(enum_name(kMethods, method)) +
                                              (bounce ? "/bounce" : "/camera") +
                                              (query == Query::any ? "/any" : "/closest");
                    benchmark::RegisterBenchmark(label.c_str(), trace_rays, path, method, bounce,
                                                 query)
                        ->Unit(benchmark::kMillisecond)
                        ->UseRealTime();
                }
    }
}

}  // namespace
}  // namespace edacrt

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    edacrt::register_all();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
