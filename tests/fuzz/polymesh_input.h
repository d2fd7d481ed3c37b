// The input of polymesh_fuzzer: the five polyMesh files in the order of
// PolyMeshText, each followed by the separator line (the seed writer joins
// them, the target splits them).
#pragma once

#include <string>
#include <string_view>

#include "cfd/mesh/poly_mesh_reader.h"

namespace kelvin::fuzz {

inline constexpr std::string_view kPolyMeshSeparator = "\n@@@@\n";

inline std::string JoinPolyMesh(const cfd::PolyMeshText& t) {
  std::string out;
  for (const std::string* part : {&t.points, &t.faces, &t.owner, &t.neighbour, &t.boundary}) {
    out += *part;
    out += kPolyMeshSeparator;
  }
  return out;
}

// Missing parts stay empty; text after the fifth separator is ignored.
inline cfd::PolyMeshText SplitPolyMesh(std::string_view in) {
  cfd::PolyMeshText t;
  for (std::string* part : {&t.points, &t.faces, &t.owner, &t.neighbour, &t.boundary}) {
    const std::size_t end = in.find(kPolyMeshSeparator);
    *part = std::string(in.substr(0, end));
    if (end == std::string_view::npos) break;
    in.remove_prefix(end + kPolyMeshSeparator.size());
  }
  return t;
}

}  // namespace kelvin::fuzz
