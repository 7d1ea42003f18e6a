#include "bench_variant.h"

#include <string>

#include "util/error.h"

namespace edacrt::cli {
namespace {

Variant parse_settings(std::string_view spec) {
    const std::size_t colon = spec.find(':');
    Variant v;
    v.label = std::string(spec);
    v.method = parse_enum_or_throw(kMethods, spec.substr(0, colon));
    const bool recursive = v.method == Method::edacrt || v.method == Method::dacrt;
    bool first = true;
    for (std::size_t at = colon; at != std::string_view::npos; first = false) {
        const std::size_t end = spec.find(':', at + 1);
        const std::string_view option = spec.substr(at + 1, end - at - 1);
        at = end;
        const std::size_t equals = option.find('=');
        if (equals == std::string_view::npos || equals == 0)
            throw InputError("'" + std::string(option) + "' is not KEY=VALUE");
        const std::string_view key = option.substr(0, equals), value = option.substr(equals + 1);
        if (v.method == Method::bvh) {
            set_bvh_option(v.bvh, key, value);
        } else if (!recursive) {
            throw InputError(std::string(enum_name(kMethods, v.method)) + " takes no options");
        } else if (key == "preset") {
            if (!first) throw InputError("preset must come first (it sets every parameter)");
            v.params = preset_params(value);
        } else if (const ParamInfo* info = find_param(key)) {
            if (v.method == Method::dacrt && dacrt_sets(key))
                throw InputError(std::string(key) +
                                 " is what makes dacrt DACRT; vary it with "
                                 "edacrt:preset=dacrt:" +
                                 std::string(key) + "=...");
            set_param(v.params, *info, value);
        } else {
            throw InputError("unknown EDACRT parameter '" + std::string(key) + "'");
        }
    }
    validate(v.params);
    return v;
}

}  // namespace

Variant parse_variant(std::string_view spec) {
    try {
        return parse_settings(spec);
    } catch (const InputError& e) {
        throw InputError("--methods " + std::string(spec) + ": " + e.what());
    }
}

}  // namespace edacrt::cli
