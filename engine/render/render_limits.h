#pragma once
// The largest max_depth and ao_samples validate(RenderSettings) accepts, for the tools whose
// own checks and widgets must agree with it (the viewer's settings table, app/settings_table.h).

namespace edacrt {

inline constexpr int kMaxMaxDepth = 1024;
inline constexpr int kMaxAoSamples = 1024;

}  // namespace edacrt
