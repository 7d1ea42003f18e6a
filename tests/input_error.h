#pragma once
// The message of an expected InputError, for tests that compare it.
#include <string>

#include "util/error.h"

namespace edacrt::test {

/// The message of the InputError `f` throws, or "" when it throws none.
template <typename F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace edacrt::test
