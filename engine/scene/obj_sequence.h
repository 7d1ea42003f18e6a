#pragma once
// OBJ files numbered by frame (name_0001.obj, name_0002.obj, ...) played as key frames.
#include <string_view>

#include "scene/animation.h"

namespace edacrt {

/// Opens "sequence:[fps=F,]pattern=P". The key frames are the files in P's directory whose
/// names P writes for some frame number (printf's %d or %0Nd), numbered without a gap; the
/// lowest is key 0 at t = 0, key k is at t = k / F (F = 24 by default). Between keys,
/// positions and shading normals go linearly (normals renormalised); after the last key it
/// holds, and duration() is its time. The scene is the first key's OBJ file (materials, camera
/// and all); every key must have its triangles (the same corners in the same order), vertex
/// count and normal layout. Keys are read when a frame needs them and at most two are held, so
/// long sequences of large meshes stream. Throws InputError for a bad spec, no matching file,
/// a gap (naming the missing file), and from frame() for a key that cannot be read or does not
/// match the first (naming both files).
AnimatedScene open_obj_sequence(std::string_view spec);

}  // namespace edacrt
