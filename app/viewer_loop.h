#pragma once
// The viewer's frame loop as a Viewer whose frame is a list of named phases (STYLE 20), each a
// function that owns its part of the loop's state:
//   input        window events, scenes asked for, the layout, picks, drags and keys
//   worker sync  the worker's newest pass, playback (sync_worker(), app/frame_phases.h)
//   panels       ImGui's widgets, which show the state and take its edits
//   submit       a new render when the settings, camera, scene or image region changed
//   jobs         the comparison and the recording, off the UI thread
//   upload       the pass, heat map and explorer tint, each when it changed
//   draw         the image region
//   outputs      saves, the UI over the image, the layout's problems
//   script       the script's step, --frames and screenshots
#include <optional>

#include "script_runner.h"
#include "viewer.h"
#include "viewer_state.h"

struct GLFWwindow;

namespace edacrt::app {

/// Runs frames in `window` (its OpenGL context current, ImGui set up) until it is closed, the
/// script or --frames end, or the script fails; returns the exit code.
int run_frames(GLFWwindow* window, ViewerState& state, std::optional<ScriptRunner>& script,
               const ViewerOptions& options);

}  // namespace edacrt::app
