// Non-throwing questions about a path the user gave. std::filesystem's
// exists() and is_directory() throw filesystem_error when the path cannot be
// examined (a name longer than the file system allows, a component that is
// not a directory, no permission); for a user's path that is the same answer
// as "not there", and the caller's own error message (naming the key and the
// value) is the one the user should see.
#pragma once

#include <filesystem>

namespace kelvin::data {

// True when `path` names an existing file or directory; false when it does not
// or cannot be examined.
bool PathExists(const std::filesystem::path& path);

// True when `path` names an existing directory; false otherwise, including
// when it cannot be examined.
bool IsExistingDirectory(const std::filesystem::path& path);

}  // namespace kelvin::data
