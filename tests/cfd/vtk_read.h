// Reading back what kelvin's VTK XML writers (cfd/io/vtu_writer.h) write,
// for the tests: a named array of the raw appended data (a UInt64 byte count,
// then the little-endian values).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace kelvin::cfd::testing {

// The bytes of the array `name` of a VTK XML file's text (empty, with a
// test failure, when there is none).
inline std::string VtkRaw(const std::string& text, const std::string& name) {
  const std::size_t tag = text.find("Name=\"" + name + "\"");
  const std::size_t data = text.find("<AppendedData encoding=\"raw\">");
  EXPECT_NE(tag, std::string::npos) << "no array " << name;
  EXPECT_NE(data, std::string::npos) << "no raw appended data";
  if (tag == std::string::npos || data == std::string::npos) return {};
  const std::size_t base = text.find('_', data) + 1;
  const std::size_t offset = std::stoull(text.substr(text.find("offset=\"", tag) + 8));
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, text.data() + base + offset, sizeof bytes);
  return text.substr(base + offset + sizeof bytes, bytes);
}

template <typename T>
std::vector<T> VtkValues(const std::string& text, const std::string& name) {
  const std::string raw = VtkRaw(text, name);
  std::vector<T> out(raw.size() / sizeof(T));
  std::memcpy(out.data(), raw.data(), out.size() * sizeof(T));
  return out;
}

// A Float64 array (the points are the array "Points", x, y, z of each).
inline std::vector<double> VtkDoubles(const std::string& text, const std::string& name) {
  return VtkValues<double>(text, name);
}
inline std::vector<std::int64_t> VtkInt64s(const std::string& text, const std::string& name) {
  return VtkValues<std::int64_t>(text, name);
}

}  // namespace kelvin::cfd::testing
