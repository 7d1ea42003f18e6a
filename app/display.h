#pragma once
// Draws the current image (render or heat map) behind the UI with the shaders in shaders/.
// Uploads a texture only when the image changes.
#include <glad/gl.h>

#include <vector>

#include "render/film.h"
#include "render/image.h"

namespace edacrt::app {

class Display {
  public:
    Display();  // needs a current OpenGL 3.3 context
    ~Display();
    Display(const Display&) = delete;
    Display& operator=(const Display&) = delete;

    void upload_render(const Image& image);
    void upload_heat(const std::vector<float>& values, int width, int height);
    /// Per pixel 0 (clear), 1 (a node's rays) or 2 (a hit found): blended over the image.
    void upload_tint(const std::vector<float>& values, int width, int height);

    struct Tone {
        float exposure = 0.0f;
        ToneMap tone_map = ToneMap::clamp;  // the shader's tone_map is its number
    };
    /// Draws the image over the whole viewport: the render, or the heat map (turbo up to
    /// heat_max; a `difference` in a diverging ramp, blue below 0 and red above).
    void draw(bool heat, const Tone& tone, float heat_max, bool heat_log,
              bool difference = false) const;
    void draw_tint() const;

  private:
    GLuint program_ = 0, vertex_array_ = 0, render_texture_ = 0, heat_texture_ = 0,
           tint_texture_ = 0;
};

}  // namespace edacrt::app
