// Replaces one benchmark's section of BENCHMARKS.md, delimited by
// <!-- name:begin --> and <!-- name:end -->, or appends it; other sections
// are left as they are. Written atomically.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include "data/schema/atomic_file.h"

namespace kelvin::bench {

inline void ReplaceMarkdownSection(const std::string& file, const std::string& name,
                                   const std::string& section) {
  const std::string begin = "<!-- " + name + ":begin -->", end = "<!-- " + name + ":end -->";
  std::string text;
  {
    std::ifstream in(file);
    std::stringstream ss;
    ss << in.rdbuf();
    text = ss.str();
  }
  const std::string block = begin + "\n" + section + end;
  const auto b = text.find(begin), e = text.find(end);
  if (b != std::string::npos && e != std::string::npos && e > b) {
    text.replace(b, e + end.size() - b, block);
  } else {
    if (text.empty())
      text = "# Benchmarks\n\nFigures measured on the project's 2-core Debian 12 machine.\n";
    text += "\n" + block + "\n";
  }
  data::WriteFileAtomically(file, text);
}

}  // namespace kelvin::bench
