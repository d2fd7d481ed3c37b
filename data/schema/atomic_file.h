// Atomic output: write beside the target, then rename over it. A crash or an
// exception before Commit() leaves any existing file untouched.
#pragma once

#include <filesystem>
#include <string_view>

namespace kelvin::data {

// A temporary path next to `target` (same directory, so rename is atomic).
std::filesystem::path TemporaryPathFor(const std::filesystem::path& target);

// Writes `content` to `target` atomically (temp file + fsync + rename).
void WriteFileAtomically(const std::filesystem::path& target, std::string_view content);

// Renames `tmp` over `target`, creating the parent directory if needed.
void CommitFile(const std::filesystem::path& tmp, const std::filesystem::path& target);

// Removes the temporary files TemporaryPathFor made in `dir` (not its
// subdirectories) for processes that no longer exist: a run killed during a
// write leaves one beside its target (a full-size checkpoint, for a large
// case), never under the target's name. Files of live processes, this one
// included, stay. Returns how many were removed.
int RemoveStaleTemporaries(const std::filesystem::path& dir);

}  // namespace kelvin::data
