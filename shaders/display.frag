#version 330 core
// The progressive render: exposure, tone mapping, sRGB. Or a heat map: counts through the
// turbo ramp (linear or logarithmic up to heat_max), or a difference of counts from blue
// (-heat_max) through white (0) to red (+heat_max).
in vec2 uv;
out vec4 colour;

uniform sampler2D image;   // RGB radiance, or the count in R
uniform int mode;          // 0: render, 1: heat map, 2: tint (blended over the image), 3: difference
uniform float exposure;    // stops
uniform int tone_map;      // 0: clamp, 1: Reinhard, 2: ACES (Narkowicz)
uniform float heat_max;
uniform int heat_log;

vec3 turbo(float t) {
    t = clamp(t, 0.0, 1.0);
    vec4 v4 = vec4(1.0, t, t * t, t * t * t);
    vec2 v2 = v4.zw * v4.z;
    const vec4 r4 = vec4(0.13572138, 4.61539260, -42.66032258, 132.13108234);
    const vec4 g4 = vec4(0.09140261, 2.19418839, 4.84296658, -14.18503333);
    const vec4 b4 = vec4(0.10667330, 12.64194608, -60.58204836, 110.36276771);
    const vec2 r2 = vec2(-152.94239396, 59.28637943);
    const vec2 g2 = vec2(4.27729857, 2.82956604);
    const vec2 b2 = vec2(-89.90310912, 27.34824973);
    return clamp(vec3(dot(v4, r4) + dot(v2, r2), dot(v4, g4) + dot(v2, g2),
                      dot(v4, b4) + dot(v2, b2)), 0.0, 1.0);
}

vec3 to_srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main() {
    if (mode == 2) {  // the explorer's tint: 1 a node's rays (yellow), 2 hits found (green)
        float v = texture(image, uv).r;
        colour = v > 1.5 ? vec4(0.2, 0.9, 0.35, 0.5) : v > 0.5 ? vec4(1.0, 0.85, 0.1, 0.45)
                                                                : vec4(0.0);
        return;
    }
    if (mode == 3) {  // as diverging() in heatmap.cpp
        float v = texture(image, uv).r;
        float t = heat_log != 0 ? log(1.0 + abs(v)) / log(1.0 + max(heat_max, 1e-6))
                                : abs(v) / max(heat_max, 1e-6);
        vec3 end = v < 0.0 ? vec3(0.23, 0.45, 0.95) : vec3(0.95, 0.3, 0.2);
        colour = vec4(mix(vec3(1.0), end, clamp(t, 0.0, 1.0)), 1.0);
        return;
    }
    if (mode == 1) {
        float v = texture(image, uv).r;
        float t = heat_log != 0 ? log(1.0 + v) / log(1.0 + max(heat_max, 1e-6))
                                : v / max(heat_max, 1e-6);
        colour = vec4(turbo(t), 1.0);  // turbo is defined in display (sRGB) space
        return;
    }
    // As tone_map() in film.cpp: from 1e6 up everything is white, and ACES's c * c stays finite.
    vec3 c = clamp(texture(image, uv).rgb * exp2(exposure), 0.0, 1e6);
    if (tone_map == 1) c = c / (1.0 + c);
    if (tone_map == 2) c = clamp(c * (2.51 * c + 0.03) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);
    colour = vec4(to_srgb(c), 1.0);
}
