// The seed corpora of the fuzz targets, written at build time by
// fuzz_make_seeds from the project's own files (data/) and writers. Each
// function fills <out>/<target>/.
#pragma once

#include <filesystem>
#include <string>

namespace kelvin::fuzz {

// Writes `bytes` to dir / name, creating dir.
void WriteSeed(const std::filesystem::path& dir, const std::string& name, const std::string& bytes);
// The bytes of a file.
std::string ReadBytes(const std::filesystem::path& path);

void WriteYamlSeeds(const std::filesystem::path& source_dir, const std::filesystem::path& out);
void WriteHullSeeds(const std::filesystem::path& out);
void WritePolyMeshSeeds(const std::filesystem::path& out);
void WriteCaptiveSeeds(const std::filesystem::path& source_dir, const std::filesystem::path& out);
void WriteBridgeSeeds(const std::filesystem::path& out);

}  // namespace kelvin::fuzz
