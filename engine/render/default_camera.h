#pragma once
// The view a scene opens with when it names none: objects are framed from outside (+z);
// interiors (Sponza, Sibenik, Conference), whose outer walls hide everything from outside,
// are seen from inside, near the middle of the floor.
#include "scene/camera.h"
#include "scene/scene.h"

namespace edacrt {

/// True when the scene encloses its centre: nearly every horizontal ray from the centre of its
/// box hits a surface facing that centre (the inside of a closed object faces away).
bool is_interior(const Scene& scene);

/// The scene's own camera; else, for an interior, a wide view from eye height above the floor
/// below the centre, looking along the longer horizontal side; else frame_box(). Y is up.
Camera default_camera(const Scene& scene);

}  // namespace edacrt
