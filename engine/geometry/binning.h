#pragma once
// Binning of centroids (Wald 2007), shared by the divide-and-conquer tracers and the BVH.

namespace edacrt {

/// The bin of a centroid already mapped to bin units, x = (c - origin) * scale, clamped to
/// [0, bins - 1]. Extreme scenes make x NaN (a centroid range that overflows gives scale 0
/// against an infinite offset; one of FLT_MIN gives an infinite scale against a zero offset):
/// NaN lands in bin 0, and no NaN or out-of-range value is converted to int (undefined
/// behaviour).
inline int bin_index(float x, int bins) {
    return x >= 0.0f ? (x < float(bins) ? int(x) : bins - 1) : 0;
}

}  // namespace edacrt
