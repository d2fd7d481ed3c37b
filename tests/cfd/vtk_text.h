// Reading back what kelvin's VTK XML writers (cfd/io/vtu_writer.h) write in
// ASCII, for the tests: a named DataArray and the points' coordinates.
#pragma once

#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

namespace kelvin::cfd::testing {

// The numbers between the DataArray's opening tag at `tag` and its end.
inline std::vector<double> DataArrayValues(const std::string& xml, std::size_t tag) {
  const std::size_t begin = xml.find('>', tag) + 1;
  std::istringstream in(xml.substr(begin, xml.find("</DataArray>", begin) - begin));
  std::vector<double> out;
  for (double v = 0.0; in >> v;) out.push_back(v);
  return out;
}

// The values of the ASCII DataArray `name` (empty when there is none).
inline std::vector<double> VtkArray(const std::string& xml, const std::string& name) {
  const std::size_t at = xml.find("Name=\"" + name + "\"");
  return at == std::string::npos ? std::vector<double>{} : DataArrayValues(xml, at);
}

// The points' coordinates, x, y, z of each (empty when there are none).
inline std::vector<double> VtkPoints(const std::string& xml) {
  const std::size_t at = xml.find("<Points>");
  return at == std::string::npos ? std::vector<double>{} : DataArrayValues(xml, xml.find("<DataArray", at));
}

}  // namespace kelvin::cfd::testing
