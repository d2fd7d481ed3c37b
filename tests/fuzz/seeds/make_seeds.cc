// fuzz_make_seeds <source dir> <output dir>: the seed corpora of every fuzz
// target, one directory per target.
#include <cstdio>
#include <exception>
#include <fstream>
#include <sstream>

#include "tests/fuzz/seeds/seeds.h"

namespace kelvin::fuzz {

void WriteSeed(const std::filesystem::path& dir, const std::string& name, const std::string& bytes) {
  std::filesystem::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary | std::ios::trunc) << bytes;
}

std::string ReadBytes(const std::filesystem::path& path) {
  std::ostringstream s;
  s << std::ifstream(path, std::ios::binary).rdbuf();
  return s.str();
}

}  // namespace kelvin::fuzz

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: fuzz_make_seeds <source dir> <output dir>\n");
    return 2;
  }
  try {
    const std::filesystem::path source = argv[1], out = argv[2];
    kelvin::fuzz::WriteYamlSeeds(source, out);
    kelvin::fuzz::WriteHullSeeds(out);
    kelvin::fuzz::WritePolyMeshSeeds(out);
    kelvin::fuzz::WriteCaptiveSeeds(source, out);
    kelvin::fuzz::WriteBridgeSeeds(out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_make_seeds: %s\n", e.what());
    return 1;
  }
  return 0;
}
