#pragma once
// Text from files (names, paths, lines) made safe to print to a terminal or a message.
#include <cstddef>
#include <string>
#include <string_view>

namespace edacrt {

/// `text` with control bytes (ESC, CR, ...) and bytes that are not valid UTF-8 escaped as \xNN,
/// cut after `max_length` bytes ("..."): a name from a file cannot send escape codes to the
/// terminal, garble or flood it.
std::string printable(std::string_view text, std::size_t max_length = std::string_view::npos);

}  // namespace edacrt
