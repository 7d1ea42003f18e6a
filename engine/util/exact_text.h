#pragma once
// Numbers as text that reads back to the same value: nine significant digits for a float,
// seventeen for a double (the fewest that always round-trip), vectors comma-separated as the
// command line's --eye X,Y,Z takes them.
#include <cstdio>
#include <glm/vec3.hpp>
#include <string>

namespace edacrt {

inline std::string exact_text(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", double(v));
    return text;
}

inline std::string exact_text(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

inline std::string exact_text(const glm::vec3& v) {
    return exact_text(v.x) + "," + exact_text(v.y) + "," + exact_text(v.z);
}

}  // namespace edacrt
