#pragma once
// Dynamic scenes: geometry as a function of time over fixed triangles. Divide-and-conquer ray
// tracing keeps no structure between frames, so a frame whose geometry changed costs it
// nothing extra, while a BVH must be rebuilt or refitted (Mora 2011; Afra 2012). `edacrt
// render --time/--frames` renders animations, `edacrt bench --dynamic` measures that cost.
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

#include "scene/scene.h"

namespace edacrt {

/// Positions (and shading normals) as a function of time t in seconds, over the triangles,
/// materials and normal layout of the scene it was made with, which stay fixed.
class Animation {
  public:
    virtual ~Animation() = default;

    /// Writes the geometry of time `t` into `scene`, the scene this animation came with, in
    /// place: positions and normals keep their storage (nothing is reallocated, and tracers'
    /// update_scene() can refit). The same t gives the same geometry, bit for bit. Throws
    /// InputError for a non-finite t, a key frame that cannot be read or does not match, and a
    /// corner or normal that comes out non-finite (naming the time and the triangle); the
    /// scene is then partly written and must not be traced. Throws std::invalid_argument for
    /// a scene of other sizes than this animation's.
    void frame(double t, Scene& scene);

    /// Seconds after which a deformation repeats (one period) or key frames end (later times
    /// hold the last key); the viewer loops over [0, duration()].
    virtual double duration() const = 0;

    /// The spec that makes this animation again, with every parameter spelled out
    /// ("wave:amplitude=0.02,wavelength=0.25,period=1,axis=y,direction=x").
    const std::string& spec() const { return spec_; }

  protected:
    /// `scene` fixes the sizes frame() accepts.
    Animation(std::string spec, const Scene& scene);

    /// Writes positions and normals of time `t` (finite) into `scene` (checked sizes).
    virtual void write_frame(double t, Scene& scene) = 0;

  private:
    std::string spec_;
    std::size_t positions_, normals_, triangles_;
};

/// A scene whose geometry is a function of time.
struct AnimatedScene {
    Scene scene;                           // the geometry of time 0; frame() writes any other
    std::unique_ptr<Animation> animation;  // null: a still scene
};

/// The scene `scene_spec` names (load_scene()) animated as `animation_spec` says:
///   wave[:amplitude=A,wavelength=L,period=P,axis=y,direction=x]
///   twist[:angle=DEG,period=P,axis=y]
///   explode[:distance=D,period=P]
///       deformations of `scene_spec` (deformations.h); lengths are fractions of its diagonal
///   FILE.json
///       objects with keyframed transforms (rigid_animation.h); `scene_spec` must be empty
///   sequence:[fps=F,]pattern=PATTERN
///       OBJ key frames such as frames/name_%04d.obj (obj_sequence.h), F per second;
///       `scene_spec` must be empty. The pattern comes last and takes the rest of the spec.
/// An empty `animation_spec` gives the still scene. The scene holds time 0. Throws InputError
/// for a bad spec, parameter or file, naming it.
AnimatedScene load_animated_scene(const std::string& scene_spec, const std::string& animation_spec);

/// Whether `spec` names an animation file (FILE.json, any case), which load_scene() refuses.
bool is_animation_file(std::string_view spec);

/// Whether `animation_spec` brings its own geometry (an animation file, an OBJ sequence) rather
/// than deforming a scene.
bool animation_has_geometry(std::string_view animation_spec);

/// One line per animation kind, for --help texts.
std::string animation_help();

}  // namespace edacrt
