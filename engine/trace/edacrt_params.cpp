#include "trace/edacrt_params.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <type_traits>

#include "util/error.h"
#include "util/exact_text.h"

namespace edacrt {
namespace {

/// A field as a double; an enum as its index.
template <auto Member>
double get_field(const EdacrtParams& p) {
    using T = std::remove_cvref_t<decltype(p.*Member)>;
    if constexpr (std::is_enum_v<T>)
        return double(int(p.*Member));
    else
        return double(p.*Member);
}

template <auto Member>
void set_field(EdacrtParams& p, double value) {
    using T = std::remove_reference_t<decltype(p.*Member)>;
    if constexpr (std::is_enum_v<T>)
        p.*Member = static_cast<T>(int(value));
    else
        p.*Member = T(value);
}

constexpr std::array<std::string_view, 3> kPresets = {"default", "paper", "dacrt"};

constexpr double kCount = 1e9;                               // upper bound of the count parameters
constexpr double kCost = std::numeric_limits<float>::max();  // costs: any finite float

using Kind = ParamInfo::Kind;

template <auto Member>
constexpr ParamInfo integer(std::string_view key, std::string_view label, std::string_view help,
                            double min, double max) {
    return {key, label, help, Kind::integer,     min,
            max, max,   {},   get_field<Member>, set_field<Member>};
}

template <auto Member>
constexpr ParamInfo real(std::string_view key, std::string_view label, std::string_view help,
                         double ui_max, double max = kCost) {
    return {key, label,  help, Kind::real,        0.0,
            max, ui_max, {},   get_field<Member>, set_field<Member>};
}

/// The names of an enum's table, stored once for ParamInfo::choices.
template <const auto& Table>
constexpr auto kChoiceNames = enum_name_array(Table);

/// A choice among the names of `Table`, which lists the enum's values in order (the parameter
/// is read and set as the value's index).
template <auto Member, const auto& Table>
constexpr ParamInfo choice(std::string_view key, std::string_view label, std::string_view help) {
    static_assert(in_enum_order(Table), "a choice's table lists its values in enum order");
    return {key,
            label,
            help,
            Kind::choice,
            0.0,
            double(Table.size() - 1),
            0.0,
            kChoiceNames<Table>,
            get_field<Member>,
            set_field<Member>};
}

const std::array<ParamInfo, 21> kParams = {
    integer<&EdacrtParams::bins>(
        "bins", "bins K",
        "K: triangles are binned by centroid into K equal bins along the split axis, giving K-1 "
        "candidate splits per node (Section 3.1, after Wald 2007).",
        2, 256),
    choice<&EdacrtParams::binning, kBinnings>(
        "binning", "binning",
        "node-box: the bins span V, the node box, on its longest axis (the paper, Section 3.1). "
        "centroids: they span the range of the centroids on that axis (Wald 2007), so no bin is "
        "empty at the ends. When all centroids land in one bin of V, node-box falls back to "
        "the centroids' range; when they coincide on V's longest axis, both bin along the axis "
        "where the centroids spread most."),
    choice<&EdacrtParams::hit_ratio, kHitRatios>(
        "hit-ratio", "hit ratio alpha",
        "Where alpha_L, alpha_R in the cost C_T + C_I (alpha_L N_L + alpha_R N_R) come from. "
        "sampled: the share of sampled rays hitting each child box (EDACRT, Section 3.2). "
        "surface-area: child area / node area, which assumes uniform rays (DACRT)."),
    integer<&EdacrtParams::sample_threshold>(
        "sample-threshold", "sample threshold",
        "Nodes with more rays than this draw sample-count random rays to estimate alpha and the "
        "order (Section 3.2; the paper uses 1000). Smaller nodes follow small-nodes.",
        1, kCount),
    integer<&EdacrtParams::sample_count>(
        "sample-count", "sample count",
        "Rays drawn (with replacement) per sampled node; each is tested against all 2(K-1) "
        "candidate boxes (Section 3.2; the paper uses 100).",
        1, 1e6),
    choice<&EdacrtParams::small_nodes, kSmallNodes>(
        "small-nodes", "small nodes",
        "How nodes with at most sample-threshold rays estimate alpha: every-ray tests all their "
        "rays (exact, 2(K-1) box tests each), capped draws at most sample-count as large nodes "
        "do, surface-area uses area ratios and the direction-sign order, scaled draws one ray "
        "in 16 (at least one, at most sample-count), so sampling costs about half what filtering "
        "the node's rays into both children costs; scaled-min draws as scaled but at least "
        "sample-min rays, and tests every ray of a node that has no more."),
    integer<&EdacrtParams::sample_min>(
        "sample-min", "min samples",
        "small-nodes=scaled-min: the fewest rays a small node estimates alpha from (scaled "
        "draws a single ray for a node of 16-31 rays, and its alpha is then 0 or 1). A node of "
        "at most this many rays tests every ray.",
        1, 1e6),
    choice<&EdacrtParams::order, kTraversalOrders>(
        "order", "traversal order",
        "Which child is visited first, so its hits cull the rays of the second (Section 3.3). "
        "sampled: the child most sampled rays enter first (EDACRT). direction-sign: by the "
        "majority sign of the rays' direction on the split axis (DACRT). left-first: no order."),
    choice<&EdacrtParams::filter_skip, kFilterSkips>(
        "filter-skip", "filter skipping",
        "When a child gets its parent's rays unfiltered (Section 3.4): if alpha > 1 - C_bv / "
        "(n_child C_child). paper: n_child C_child is what the child spends on a ray that misses "
        "it, 2 C_bv (its two box tests) for an inner child, N C_I for a child that will be a "
        "leaf. triangles: N C_child at any depth. off: always filter (DACRT)."),
    choice<&EdacrtParams::second_child, kSecondChildren>(
        "second-child", "second child",
        "When the second child gets its rays. after-first: all of them once the first child is "
        "done, so its hits cull them (the paper, Section 3.3); subtrees run one after the other. "
        "split: the rays that missed the first child's box go to the second child at once, as a "
        "task beside the first child (no hit there can cull them), the others once it is done; "
        "the same culling and box tests, the second child recursing twice, and subtrees in "
        "parallel. Only where it can pay: with 512 missed rays or more, and on more than one "
        "thread (on one, split is after-first)."),
    choice<&EdacrtParams::far_child, kFarChildren>(
        "far-child", "far child",
        "Not in the paper: what the cost counts of the child visited second. paper: alpha, "
        "every sampled ray that hits its box. unstopped: only the sampled rays that reach its box "
        "without entering the first child's box before it (those are taken as stopped by a hit "
        "there, as the first child's hits cull them); rays that start inside both boxes count "
        "for the side they head to, as in the order. Needs sampled hit ratios."),
    integer<&EdacrtParams::leaf_rays>(
        "leaf-rays", "leaf rays", "Brute force when a node has at most this many rays.", 1, kCount),
    integer<&EdacrtParams::leaf_tris>(
        "leaf-tris", "leaf triangles",
        "Brute force when a node has at most this many triangles and at most leaf-tris-rays "
        "rays reach it (or always, with leaf-tris-rays 0).",
        1, kCount),
    integer<&EdacrtParams::leaf_tris_rays>(
        "leaf-tris-rays", "leaf-tris rays",
        "Not in the paper: a node of at most leaf-tris triangles is a leaf only when at most "
        "this many rays reach it; with more, it splits on down to 2 triangles, since each ray "
        "then costs a leaf N triangle tests where a split costs it two box tests, and the "
        "split's binning is shared by many rays (the Cornell box's wide walls get thousands of "
        "rays per node, the bunny's leaves tens). 0: whatever the rays (the paper).",
        0, kCount),
    integer<&EdacrtParams::cost_leaf_max_tris>(
        "cost-leaf-max-tris", "cost-leaf max tris",
        "Not in the paper: nodes with at most this many triangles become leaves when no split "
        "costs less than C_I N per ray (the cost prices both children as leaves, so in large "
        "nodes it would stop the recursion early). 0, the default, turns it off.",
        0, kCount),
    real<&EdacrtParams::cost_traversal>(
        "c-t", "C_T", "C_T: cost per ray of a split, in ray-triangle tests (Section 3.2).", 16.0),
    real<&EdacrtParams::cost_intersect>("c-i", "C_I",
                                        "C_I: cost of one ray-triangle test (Section 3.2).", 16.0),
    real<&EdacrtParams::cost_filter>(
        "c-bv", "C_bv", "C_bv: cost of filtering one ray against a child box (Section 3.4).", 16.0),
    real<&EdacrtParams::cost_child>(
        "c-child", "C_child",
        "C_child: per-triangle cost of an unfiltered ray, for filter-skip=triangles (Section "
        "3.4).",
        16.0),
    real<&EdacrtParams::presplit>(
        "presplit", "pre-split",
        "Not in the paper: before the recursion, large triangles are cut into pieces (early split "
        "clipping, Ernst & Greiner 2007, grid-aligned planes after Karras & Aila 2013), at most "
        "this many extra pieces per triangle in all, shared by the box areas of the triangles "
        "whose box is at least twice the mean. A piece's box is "
        "that of the clipped part, so a long wall or floor no longer widens every node it "
        "crosses; a hit is still the whole triangle's. 0 turns it off.",
        2.0, 8.0),
    integer<&EdacrtParams::seed>(
        "sampling-seed", "sampling seed",
        "Seed of the per-node ray sampling; a node's draws depend only on it, the node's depth "
        "and its ray count.",
        0, 4294967295.0),
};

void require(bool ok, const std::string& what) {
    if (!ok) throw InputError("EDACRT parameter " + what);
}

std::string list(std::span<const std::string_view> names) {
    std::string out;
    for (std::string_view name : names) out += std::string(out.empty() ? "" : "|") += name;
    return out;
}

std::string range_text(const ParamInfo& info) {
    std::ostringstream out;
    out.precision(10);
    out << "[" << info.min << ", " << info.max << "]";
    return out.str();
}

}  // namespace

EdacrtParams paper_params() {
    EdacrtParams p;
    p.binning = Binning::node_box;
    p.small_nodes = SmallNodes::every_ray;
    p.filter_skip = FilterSkip::paper;
    p.cost_leaf_max_tris = 0;
    p.sample_threshold = 1000;
    p.sample_count = 100;
    p.second_child = SecondChild::after_first;
    p.presplit = 0.0f;
    p.far_child = FarChild::paper;
    p.leaf_tris = 4;
    p.leaf_tris_rays = 0;
    return p;
}

EdacrtParams dacrt_params(EdacrtParams params) {
    params.hit_ratio = HitRatio::surface_area;
    params.order = TraversalOrder::direction_sign;
    params.filter_skip = FilterSkip::off;
    return params;
}

bool dacrt_sets(std::string_view key) {
    return key == "hit-ratio" || key == "order" || key == "filter-skip";
}

EdacrtParams preset_params(std::string_view name) {
    if (name == kPresets[0]) return EdacrtParams{};
    if (name == kPresets[1]) return paper_params();
    if (name == kPresets[2]) return dacrt_params();
    throw InputError("unknown preset '" + std::string(name) + "' (" + list(kPresets) + ")");
}

std::span<const std::string_view> preset_names() { return kPresets; }

std::span<const ParamInfo> edacrt_param_info() { return kParams; }

const ParamInfo* find_param(std::string_view key) {
    for (const ParamInfo& info : kParams)
        if (info.key == key) return &info;
    return nullptr;
}

void validate(const EdacrtParams& p) {
    for (const ParamInfo& info : kParams) {
        const double value = info.get(p);
        if (info.kind == Kind::choice)
            require(value >= info.min && value <= info.max,
                    std::string(info.key) + " must be one of " + list(info.choices));
        else
            require(std::isfinite(value) && value >= info.min && value <= info.max,
                    std::string(info.key) + " must be in " + range_text(info));
    }
    require(p.cost_intersect > 0.0f, "c-i (C_I) must be positive");
    require(p.cost_child > 0.0f, "c-child (C_child) must be positive");
}

void set_param(EdacrtParams& p, const ParamInfo& info, std::string_view text) {
    const auto fail = [&](const std::string& why) {
        throw InputError("EDACRT parameter " + std::string(info.key) + ": '" + std::string(text) +
                         "' " + why);
    };
    if (info.kind == Kind::choice) {
        for (std::size_t i = 0; i < info.choices.size(); ++i)
            if (info.choices[i] == text) return info.set(p, double(i));
        fail("is not one of " + list(info.choices));
    }
    const std::optional<double> number = parse_number(text);
    if (!number) fail("is not a number");
    const double value = *number;
    if (info.kind == Kind::integer && value != std::floor(value)) fail("is not an integer");
    if (value < info.min || value > info.max) fail("is outside " + range_text(info));
    info.set(p, value);
}

std::string param_text(const EdacrtParams& p, const ParamInfo& info) {
    const double value = info.get(p);
    if (info.kind == Kind::choice) return std::string(info.choices[std::size_t(value)]);
    std::ostringstream out;
    out.precision(9);
    out << value;
    return out.str();
}

NodeSampling node_sampling(const EdacrtParams& p, std::size_t rays) {
    if (rays > p.sample_threshold) return {p.sample_count, false};
    const auto all = std::uint32_t(rays);  // at most sample_threshold
    switch (p.small_nodes) {
        case SmallNodes::every_ray:
            return {all, true};
        case SmallNodes::capped:
            return rays > p.sample_count ? NodeSampling{p.sample_count, false}
                                         : NodeSampling{all, true};
        case SmallNodes::surface_area:
            return {0, false};
        case SmallNodes::scaled:
            return {std::uint32_t(
                        std::clamp<std::size_t>(rays / kScaledSampleShare, 1, p.sample_count)),
                    false};
        case SmallNodes::scaled_min: {
            // A node of at most count rays tests each once (drawing would repeat some).
            const std::size_t count = std::max<std::size_t>(
                p.sample_min, std::min<std::size_t>(rays / kScaledSampleShare, p.sample_count));
            return count >= rays ? NodeSampling{all, true}
                                 : NodeSampling{std::uint32_t(count), false};
        }
    }
    return {all, true};
}

std::uint32_t always_leaf_tris(const EdacrtParams& p) {
    return p.leaf_tris_rays == 0 ? p.leaf_tris : std::min(p.leaf_tris, kAlwaysLeafTris);
}

bool triangle_leaf(const EdacrtParams& p, std::size_t triangles, std::size_t rays) {
    return triangles <= always_leaf_tris(p) ||
           (triangles <= p.leaf_tris && rays <= p.leaf_tris_rays);
}

float filter_skip_threshold(const EdacrtParams& p, std::uint32_t child_triangles,
                            std::size_t rays) {
    // Never skip when filtering is off, or costs nothing (C_bv = 0).
    if (p.filter_skip == FilterSkip::off || p.cost_filter == 0.0f) return 2.0f;
    // Filtering costs C_bv for every ray; passing a ray unfiltered costs, if it misses the
    // child (1 - alpha of the rays), what the child then spends on it, n_child C_child. Skip
    // when (1 - alpha) n_child C_child < C_bv, i.e. alpha > 1 - C_bv / (n_child C_child).
    // Paper: the child gets all the node's rays, more than leaf_rays, so the count thresholds
    // make it a leaf exactly when triangle_leaf() says so; a leaf tests each ray
    // against those, an inner child against its two children's boxes. (A child that ends as
    // a leaf otherwise, unsplittable or by the optional cost leaf, is priced as an inner one.)
    const float n = float(child_triangles);
    const float wasted = p.filter_skip == FilterSkip::triangles    ? n * p.cost_child
                         : triangle_leaf(p, child_triangles, rays) ? n * p.cost_intersect
                                                                   : 2.0f * p.cost_filter;
    return 1.0f - p.cost_filter / wasted;
}

bool cost_leaf_tested(const EdacrtParams& p, std::uint32_t triangles) {
    return p.cost_leaf_max_tris > 0 && triangles <= p.cost_leaf_max_tris;
}

std::optional<std::string_view> param_no_effect_reason(const EdacrtParams& p, const ParamInfo& info,
                                                       int threads) {
    const std::string_view key = info.key;
    // Nodes sample rays only for a sampled hit ratio or order, and only nodes of more than
    // leaf_rays rays and always_leaf_tris() triangles choose a split at all.
    const bool sampling = p.hit_ratio == HitRatio::sampled || p.order == TraversalOrder::sampled;
    const std::uint64_t fewest_sampled = std::uint64_t(p.leaf_rays) + 1;
    // Small nodes that draw sample_count rays whatever their size, as large ones do.
    const bool small_as_large =
        (p.small_nodes == SmallNodes::capped && p.sample_count < fewest_sampled) ||
        (p.small_nodes == SmallNodes::scaled &&
         std::uint64_t(p.sample_count) * kScaledSampleShare <= fewest_sampled);
    // The cost leaf is tested in nodes that choose a split: with leaf_tris_rays, those of
    // 3..leaf_tris triangles that many rays reach too.
    const bool cost_leaf = p.cost_leaf_max_tris > always_leaf_tris(p);
    const bool free_filter = p.cost_filter == 0.0f;

    if ((key == "sample-threshold" || key == "sample-count" || key == "small-nodes" ||
         key == "sample-min" || key == "sampling-seed") &&
        !sampling)
        return "neither the hit ratio nor the traversal order is sampled: no node samples rays";
    if (key == "sample-threshold" && small_as_large)
        return "every node that samples (more than leaf-rays rays) draws sample-count rays "
               "under this small-node policy, small or large";
    if (key == "sample-min" && p.small_nodes != SmallNodes::scaled_min)
        return "only small-nodes=scaled-min draws at least sample-min rays";
    if ((key == "small-nodes" || key == "sample-min") && p.sample_threshold <= p.leaf_rays)
        return "no node that samples is small: nodes of at most sample-threshold rays are "
               "leaves (leaf-rays)";
    if (key == "leaf-tris-rays" && p.leaf_tris <= kAlwaysLeafTris)
        return "nodes of at most leaf-tris triangles (2 or fewer) are leaves whatever their rays";
    if (key == "far-child" && p.hit_ratio != HitRatio::sampled)
        return "area hit ratios have no sampled rays to drop from the second child's term";
    if (key == "second-child" && threads <= 1)
        return "on one thread the second child's rays all wait for the first child (split "
               "needs a second thread for its task)";
    // Every candidate pays the same C_T and its tests are all priced by C_I, so the cheapest
    // split is the one of fewest expected tests; the costs decide only against a leaf.
    if (key == "c-t" && !cost_leaf)
        return "C_T is the same for every candidate split, so it only decides against a leaf "
               "(cost C_I N): set cost-leaf max tris above the triangles of a node that is a "
               "leaf whatever its rays (leaf triangles, or 2 with leaf-tris rays)";
    if (key == "c-i" && !cost_leaf && (p.filter_skip != FilterSkip::paper || free_filter))
        return "C_I prices every candidate split alike, so it only decides against a leaf "
               "(cost-leaf max tris above the triangles of a node that is a leaf whatever its "
               "rays) and in filter-skip=paper's threshold "
               "for a leaf child";
    if (key == "c-bv" && p.filter_skip == FilterSkip::off)
        return "filter skipping is off: every child's rays are filtered";
    if (key == "c-child" && p.filter_skip != FilterSkip::triangles)
        return "only filter-skip=triangles prices a child by C_child";
    if ((key == "c-child" || key == "filter-skip") && free_filter)
        return "C_bv is 0: filtering costs nothing, so it is never skipped";
    return std::nullopt;
}

}  // namespace edacrt
