// The browser display's page and script (bridge/display/), compiled into
// kelvin so that it serves them itself, with no network at run time.
#pragma once

#include <string_view>

namespace kelvin::bridge {

std::string_view DisplayPageHtml();
std::string_view DisplayPageScript();

}  // namespace kelvin::bridge
