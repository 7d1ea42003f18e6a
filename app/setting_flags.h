#pragma once
// The viewer's command-line flags for its settings, one --KEY per viewer_settings() entry
// (app/settings_table.h): the flag's help, its check and the value it sets are the entry's.
#include <CLI/CLI.hpp>

#include "settings_table.h"

namespace edacrt::app {

/// Adds --KEY for every setting: a value that the setting refuses is a usage error naming the
/// flag; a toggle's flag alone means 1 (--KEY=0 turns it off).
void add_setting_flags(CLI::App& app, GivenSettings& given);

}  // namespace edacrt::app
