#pragma once
// The parameters of the divide-and-conquer recursion, each described once (ParamInfo): the CLI
// flags, the viewer's widgets and tooltips, the viewer's script keys and the range checks are
// all generated from edacrt_param_info().
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "util/enum_table.h"

namespace edacrt {

/// Where a split's hit ratios alpha_L, alpha_R come from (Section 3.2).
enum class HitRatio : std::uint8_t {
    sampled,       // EDACRT: the share of sampled rays that hit each child box
    surface_area,  // DACRT: child box area / node box area (uniform rays, Wald 2007)
};
inline constexpr auto kHitRatios = enum_table<HitRatio>(
    "hit ratio", {{HitRatio::sampled, "sampled"}, {HitRatio::surface_area, "surface-area"}});

/// Which child is visited first (Section 3.3).
enum class TraversalOrder : std::uint8_t {
    sampled,         // EDACRT: the child most sampled rays enter first
    direction_sign,  // DACRT: the majority sign of the rays' direction on the split axis
    left_first,      // no ordering: always the lower child first
};
inline constexpr auto kTraversalOrders = enum_table<TraversalOrder>(
    "traversal order", {{TraversalOrder::sampled, "sampled"},
                        {TraversalOrder::direction_sign, "direction-sign"},
                        {TraversalOrder::left_first, "left-first"}});

/// When rays are passed to a child without filtering (Section 3.4).
enum class FilterSkip : std::uint8_t {
    off,        // DACRT: always filter
    paper,      // alpha > 1 - C_bv / (n_child C_child), n_child C_child what the child spends
                // on a ray that misses it: two box tests for an inner child, its triangles for
                // a leaf
    triangles,  // alpha > 1 - C_bv / (N C_child), N the child's triangle count, at any depth
};
inline constexpr auto kFilterSkips = enum_table<FilterSkip>(
    "filter skipping",
    {{FilterSkip::off, "off"}, {FilterSkip::paper, "paper"}, {FilterSkip::triangles, "triangles"}});

/// How nodes with at most sample_threshold rays estimate their hit ratios.
enum class SmallNodes : std::uint8_t {
    every_ray,     // test all of the node's rays against every candidate box
    capped,        // draw at most sample_count rays, as large nodes do
    surface_area,  // surface-area ratios (and the direction-sign order)
    scaled,        // draw one ray in kScaledSampleShare (at least one, at most sample_count)
    scaled_min,    // as scaled, but at least sample_min rays; every ray in nodes of no more
};
inline constexpr auto kSmallNodes =
    enum_table<SmallNodes>("small-node policy", {{SmallNodes::every_ray, "every-ray"},
                                                 {SmallNodes::capped, "capped"},
                                                 {SmallNodes::surface_area, "surface-area"},
                                                 {SmallNodes::scaled, "scaled"},
                                                 {SmallNodes::scaled_min, "scaled-min"}});

/// SmallNodes::scaled: a sampled ray is tested against the 2(K-1) candidate boxes, two
/// eight-lane tests for K = 8, as many as filtering eight rays into both children; one sample
/// per sixteen rays keeps the sampling at half the node's filtering.
inline constexpr std::uint32_t kScaledSampleShare = 16;

/// The axis and range of the K bins (Section 3.1).
enum class Binning : std::uint8_t {
    node_box,   // the paper: K equal bins across V, the node box, on its longest axis
    centroids,  // Wald 2007: K equal bins across the range the centroids span on that axis
};
inline constexpr auto kBinnings = enum_table<Binning>(
    "binning", {{Binning::node_box, "node-box"}, {Binning::centroids, "centroids"}});

/// What the cost counts of the child visited second (not in the paper; see choose_split).
enum class FarChild : std::uint8_t {
    paper,      // alpha: every sampled ray that hits its box (Section 3.2)
    unstopped,  // only the sampled rays that do not enter the first child's box before it
};
inline constexpr auto kFarChildren = enum_table<FarChild>(
    "far-child cost", {{FarChild::paper, "paper"}, {FarChild::unstopped, "unstopped"}});

/// When the second child gets its rays.
enum class SecondChild : std::uint8_t {
    after_first,  // the paper: all of them once the first child is done (its hits cull them)
    split,        // at once, as a task beside the first child, the rays that missed the first
                  // child's box (no hit there can cull them); the rest once it is done
};
inline constexpr auto kSecondChildren = enum_table<SecondChild>(
    "second-child policy",
    {{SecondChild::after_first, "after-first"}, {SecondChild::split, "split"}});

/// Parameters of EDACRT (Nabata, Iwasaki, Dobashi, Nishita, HPG 2013). Section numbers refer to
/// that paper. dacrt_params() turns the same recursion into object-partitioning DACRT (Afra
/// 2012), paper_params() sets the paper's choices; README lists where the defaults differ.
struct EdacrtParams {
    int bins = 8;  // K
    std::uint32_t sample_threshold = 1000;
    std::uint32_t sample_count = 100;
    SmallNodes small_nodes = SmallNodes::scaled_min;
    std::uint32_t sample_min = 16;  // SmallNodes::scaled_min
    std::uint32_t leaf_rays = 16;
    std::uint32_t leaf_tris = 8;
    std::uint32_t leaf_tris_rays = 256;    // 0: a leaf at leaf_tris whatever its rays (the paper)
    std::uint32_t cost_leaf_max_tris = 0;  // 0: no leaves by cost (the paper)
    float cost_traversal = 2.0f;           // C_T
    float cost_intersect = 1.0f;           // C_I
    // C_bv: a ray-box test costs about 0.6 of a ray-triangle test in the SIMD kernels (1.7 ns
    // per filtered ray, 2.4-3.2 ns per ray-triangle pair: bench/README.md, the kernels).
    float cost_filter = 0.5f;
    float cost_child = 1.0f;  // C_child (FilterSkip::triangles)
    HitRatio hit_ratio = HitRatio::sampled;
    TraversalOrder order = TraversalOrder::sampled;
    FilterSkip filter_skip = FilterSkip::paper;
    Binning binning = Binning::node_box;
    SecondChild second_child = SecondChild::split;
    FarChild far_child = FarChild::paper;
    float presplit = 0.1f;   // extra triangle pieces per triangle (not in the paper; 0: off)
    std::uint32_t seed = 1;  // of the per-node ray sampling

    bool operator==(const EdacrtParams&) const = default;
};

/// The paper's choices: the defaults, but every ray sampled in small nodes, the second child
/// after the first, no pre-split triangles, and leaves of 4 triangles whatever their rays.
EdacrtParams paper_params();

/// DACRT (Afra 2012) on the same recursion: surface-area ratios, direction-sign order, always
/// filtering. Other fields are taken from `params`.
EdacrtParams dacrt_params(EdacrtParams params = {});

/// The parameters dacrt_params() sets (by key), which the dacrt method cannot take.
bool dacrt_sets(std::string_view key);

/// The named presets: "default", "paper", "dacrt"; throws InputError for another name.
EdacrtParams preset_params(std::string_view name);
std::span<const std::string_view> preset_names();

/// Throws InputError naming the first parameter out of range.
void validate(const EdacrtParams& params);

/// The rays a node samples to estimate alpha and the order (Section 3.2): `count` rays drawn
/// at random (with replacement), or, when `every_ray`, each of its rays once.
struct NodeSampling {
    std::uint32_t count = 0;
    bool every_ray = false;
};

/// The sampling of a node of `rays` rays under params' sample_threshold, sample_count and
/// small_nodes; count 0 when the node takes surface-area ratios instead.
NodeSampling node_sampling(const EdacrtParams& params, std::size_t rays);

/// Splitting two triangles costs every ray two box tests to spare it at most one triangle
/// test, so a node of so few is a leaf however many rays reach it.
inline constexpr std::uint32_t kAlwaysLeafTris = 2;

/// The most triangles a node can hold and be a leaf however many rays reach it: leaf_tris
/// with leaf_tris_rays 0 (the paper), else at most kAlwaysLeafTris.
std::uint32_t always_leaf_tris(const EdacrtParams& params);

/// Whether a node of `triangles` triangles and `rays` rays is a leaf by its triangle count:
/// at most always_leaf_tris(), or at most leaf_tris reached by at most leaf_tris_rays rays.
bool triangle_leaf(const EdacrtParams& params, std::size_t triangles, std::size_t rays);

/// Section 3.4: the hit ratio above which a child's rays pass to it unfiltered (never, above
/// 1, with FilterSkip::off); the child holds `child_triangles` triangles and, unfiltered, gets
/// `rays` rays.
float filter_skip_threshold(const EdacrtParams& params, std::uint32_t child_triangles,
                            std::size_t rays);

/// Whether a node of `triangles` triangles becomes a leaf when no split costs less than C_I N
/// (cost_leaf_max_tris; 0 turns the test off).
bool cost_leaf_tested(const EdacrtParams& params, std::uint32_t triangles);

/// One parameter, described once.
struct ParamInfo {
    enum class Kind { integer, real, choice };
    std::string_view key;    // CLI flag without "--", viewer script key
    std::string_view label;  // viewer label: the paper's symbol where it has one
    std::string_view help;   // meaning, unit, the paper's section
    Kind kind;
    double min, max;                            // valid range (integer, real)
    double ui_max;                              // slider end in the viewer (real)
    std::span<const std::string_view> choices;  // names, in enum order (choice; its EnumTable)
    double (*get)(const EdacrtParams&);         // a choice as its index
    void (*set)(EdacrtParams&, double);
};

std::span<const ParamInfo> edacrt_param_info();

/// The parameter with this key, or null.
const ParamInfo* find_param(std::string_view key);

/// Sets a parameter from text (a number, or a choice's name); throws InputError that names the
/// parameter and its valid values.
void set_param(EdacrtParams& params, const ParamInfo& info, std::string_view text);

/// The parameter's value as set_param() reads it.
std::string param_text(const EdacrtParams& params, const ParamInfo& info);

/// Why `info` cannot change the hits or the counters of a trace, whatever its value, under the
/// other parameters of `params` on `threads` worker threads; nothing when it may. (It may still
/// change the costs the recursion explorer shows.)
std::optional<std::string_view> param_no_effect_reason(const EdacrtParams& params,
                                                       const ParamInfo& info, int threads);

}  // namespace edacrt
