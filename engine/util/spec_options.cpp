#include "util/spec_options.h"

namespace edacrt {

SpecOptions::SpecOptions(std::string_view spec, std::string_view list) : spec_(spec) {
    while (!list.empty()) {
        const std::size_t comma = list.find(',');
        const std::string_view item = list.substr(0, comma);
        const std::size_t eq = item.find('=');
        if (eq == std::string_view::npos || eq == 0)
            throw InputError(spec_ + ": expected key=value, got '" + std::string(item) + "'");
        const std::string key(item.substr(0, eq));
        if (!values_.emplace(key, std::string(item.substr(eq + 1))).second)
            throw InputError(spec_ + ": '" + key + "' is given twice");
        list = comma == std::string_view::npos ? std::string_view() : list.substr(comma + 1);
    }
}

std::string SpecOptions::text(const char* key, std::string fallback) {
    const auto it = values_.find(key);
    if (it == values_.end()) return fallback;
    std::string value = it->second;
    values_.erase(it);
    return value;
}

void SpecOptions::finish() const {
    if (!values_.empty())
        throw InputError(spec_ + ": unknown option '" + values_.begin()->first + "'");
}

std::string shortest_text(double x) {
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, x);
    return std::string(text, result.ptr);
}

}  // namespace edacrt
