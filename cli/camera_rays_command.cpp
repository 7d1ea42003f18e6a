// edacrt camera-rays: writes a ray file of one camera ray per pixel centre, for `edacrt trace`.
#include <iostream>

#include "camera_flags.h"
#include "commands.h"
#include "common_options.h"
#include "trace/ray_file.h"

namespace edacrt::cli {
namespace {

struct CameraRaysOptions {
    std::string scene;
    int width = 1024;
    int height = 1024;
    CameraOptions camera;
    std::string out;
};

void run(const CameraRaysOptions& o) {
    const std::vector<NamedPath> outputs = {{"--out", o.out}};
    check_distinct_files(outputs, {{"--scene", o.scene}});
    const Scene scene = load_scene_verbose(o.scene);
    check_outputs_spare_scene(outputs, scene);
    const Camera camera = choose_camera(scene, o.camera);
    const std::vector<Ray> rays = PinholeProjection(camera, o.width, o.height).pixel_centre_rays();
    write_rays(o.out, rays);
    std::cout << "wrote " << rays.size() << " camera rays (" << o.width << "x" << o.height
              << ", row by row from the top-left) to " << o.out << "\n";
}

}  // namespace

std::function<void()> add_camera_rays_command(CLI::App& app) {
    auto options = std::make_shared<CameraRaysOptions>();
    CameraRaysOptions& o = *options;
    CLI::App* command = app.add_subcommand(
        "camera-rays",
        "Write one camera ray per pixel centre to a ray file (for 'edacrt trace').\n"
        "Example: edacrt camera-rays --scene assets/spot/spot.obj --out out/spot_1m.rays");
    command->add_option("--scene", o.scene, "OBJ file or builtin:NAME (frames the camera)")
        ->required();
    flags::add_image_size_options(*command, o.width, o.height);
    flags::add_camera_options(*command, o.camera);
    command->add_option("--out", o.out, "output ray file")->required();
    return [options] { run(*options); };
}

}  // namespace edacrt::cli
