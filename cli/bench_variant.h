#pragma once
// A variant of a method for `edacrt bench --methods`, written METHOD[:KEY=VALUE]...: the
// switch sweep and the comparisons of bench/ time methods with settings other than their
// defaults in one process, on the same rays.
#include <string_view>

#include "bench_report.h"

namespace edacrt::cli {

/// The variant a spec names; its label is the spec. edacrt and dacrt take the EDACRT parameters
/// by their flag names, `preset=NAME` first if at all (dacrt: not the three that make it DACRT);
/// bvh takes set_bvh_option()'s keys; embree and naive take none. Throws InputError.
Variant parse_variant(std::string_view spec);

}  // namespace edacrt::cli
