#include "camera_flags.h"

namespace edacrt::flags {

void add_camera_options(CLI::App& command, CameraOptions& o) {
    for (const CameraParam& param : camera_params()) {
        CLI::Option* option = command.add_option("--" + std::string(param.key), o.*param.given,
                                                 std::string(param.help));
        option->expected(int(param.count));
        if (param.count > 1) option->delimiter(',');
    }
}

void add_image_size_options(CLI::App& command, int& width, int& height) {
    command.add_option("--width", width, "image width in pixels")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    command.add_option("--height", height, "image height in pixels")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
}

}  // namespace edacrt::flags
