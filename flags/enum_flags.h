#pragma once
// Flags that take an enum by name, in both tools: the help lists the names (with their short
// descriptions) and shows the default, both from the enum's table (util/enum_table.h).
#include <CLI/CLI.hpp>
#include <string>

#include "util/enum_table.h"
#include "util/error.h"

namespace edacrt::flags {

/// "HELP: a (what a is), b, c": the help of a flag or a list that takes the names of `table`.
template <typename E, std::size_t N>
std::string enum_option_help(const std::string& help, const EnumTable<E, N>& table) {
    return help + ": " + enum_help(table);
}

/// Adds `flag`, which sets `value` to the value its name names; `value` holds the default. An
/// unknown name throws InputError ("--FLAG: unknown WHAT 'x' (known: ...)") from
/// parse_command_line(), which reports it as a usage error.
template <typename E, std::size_t N>
CLI::Option* add_enum_option(CLI::App& command, const std::string& flag, E& value,
                             const EnumTable<E, N>& table, const std::string& help) {
    return command
        .add_option_function<std::string>(
            flag,
            [&value, &table, flag](const std::string& name) {
                try {
                    value = parse_enum_or_throw(table, name);
                } catch (const InputError& e) {  // named as CLI11 names a flag it refuses
                    throw InputError(flag + ": " + e.what());
                }
            },
            enum_option_help(help, table))
        ->default_str(std::string(enum_name(table, value)));
}

}  // namespace edacrt::flags
