#pragma once
// The phases of the viewer's frame that need no window (tested headless): taking the worker's
// newest pass into the state, and turning the state into the request the worker should render. The
// loop (app/viewer_loop.cpp) runs them between its window-bound phases.
#include <cstdint>
#include <memory>
#include <optional>

#include "render_worker.h"
#include "viewer_state.h"

namespace edacrt::app {

/// Worker sync: takes `latest` (the worker's newest frame, or null) when it answers the request in
/// force, `request_id`: its error, or its pass as the one shown (with the convergence point it adds
/// and the animation's frame time); then moves the animation on by `dt` seconds and marks a
/// recording of another view stale.
void sync_worker(ViewerState& state, const std::shared_ptr<const Frame>& latest,
                 std::uint64_t request_id, double dt);

/// Submit: the request for the current settings, camera, scene and an image region of width x
/// height pixels when it differs from the one submitted (or none was, `first`), after
/// fit_resolution(); nothing when the render in progress is still what is asked for.
std::optional<RenderRequest> changed_request(ViewerState& state, int width, int height, bool first);

}  // namespace edacrt::app
