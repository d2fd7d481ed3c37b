#include "simulator/mmg/derivative_check_io.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "data/schema/atomic_file.h"
#include "data/schema/config.h"
#include "data/schema/errors.h"

namespace kelvin::sim {

namespace {

// One YAML scalar, quoted as the emitter sees fit.
std::string Scalar(const std::string& value) {
  YAML::Emitter e;
  e << value;
  return e.c_str();
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) {
      lines.push_back(text.substr(start));
      break;
    }
    lines.push_back(text.substr(start, end + 1 - start));  // with its '\n'
    start = end + 1;
  }
  return lines;
}

// A top-level `check:` key (column 0, plain or quoted).
bool IsCheckKey(const std::string& line) {
  for (const char* key : {"check", "\"check\"", "'check'"}) {
    const std::string k(key);
    if (line.compare(0, k.size(), k) != 0) continue;
    std::size_t i = k.size();
    while (i < line.size() && line[i] == ' ') ++i;
    if (i < line.size() && line[i] == ':' &&
        (i + 1 == line.size() || line[i + 1] == ' ' || line[i + 1] == '\n' || line[i + 1] == '\r')) {
      return true;
    }
  }
  return false;
}

bool IsBlank(const std::string& line) { return line.find_first_not_of(" \t\r\n") == std::string::npos; }
bool IsIndented(const std::string& line) { return !line.empty() && (line[0] == ' ' || line[0] == '\t'); }

}  // namespace

std::string FormatDerivativeCheck(const DerivativeCheck& c) {
  std::string s = "check:\n";
  s += fmt::format("  passed: {}\n", c.passed ? "true" : "false");
  s += fmt::format("  reference: {}\n", Scalar(c.reference));
  s += fmt::format("  date: {}\n", Scalar(c.date));
  if (c.summary.find('\n') == std::string::npos) {
    s += fmt::format("  summary: {}\n", Scalar(c.summary));
  } else {
    // A literal block, without the final line break (|-).
    s += "  summary: |-\n";
    std::istringstream in(c.summary);
    for (std::string line; std::getline(in, line);) s += "    " + line + "\n";
  }
  return s;
}

std::string WithDerivativeCheck(const std::string& text, const DerivativeCheck& check, const std::string& source) {
  const DerivativeSet before = LoadDerivativeSet(data::ConfigNode::LoadString(text, source), source);
  const std::vector<std::string> lines = Lines(text);
  std::size_t begin = lines.size(), end = lines.size();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!IsCheckKey(lines[i])) continue;
    begin = i;
    end = i + 1;
    while (end < lines.size() && (IsIndented(lines[end]) || IsBlank(lines[end]))) ++end;
    while (end > begin + 1 && IsBlank(lines[end - 1])) --end;  // blank lines stay with what follows
    break;
  }
  std::string out;
  for (std::size_t i = 0; i < begin; ++i) out += lines[i];
  if (!out.empty() && out.back() != '\n') out += '\n';
  out += FormatDerivativeCheck(check);
  for (std::size_t i = end; i < lines.size(); ++i) out += lines[i];

  // The edited file must load as the same set with this check.
  DerivativeSet after;
  try {
    after = LoadDerivativeSet(data::ConfigNode::LoadString(out, source), source);
  } catch (const ConfigError& e) {
    throw ConfigError(
        fmt::format("{}: cannot add a check section to this file's layout ({}); expected a "
                    "derivative set written as a block map, as kelvin identify writes it",
                    source, e.what()));
  }
  const bool same_check = after.check && after.check->passed == check.passed &&
                          after.check->reference == check.reference && after.check->date == check.date &&
                          after.check->summary == check.summary;
  bool same_hull = after.name == before.name;
  for (int i = 0; i < HullCoefficients<double>::kCount; ++i) same_hull = same_hull && after.hull[i] == before.hull[i];
  if (!same_check || !same_hull) {
    throw ConfigError(
        fmt::format("{}: cannot add a check section to this file's layout (the edited file does not "
                    "read back as the same set with the new check); expected a derivative set "
                    "written as a block map, as kelvin identify writes it",
                    source));
  }
  return out;
}

void WriteDerivativeCheck(const std::filesystem::path& path, const DerivativeCheck& check) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(fmt::format("{}: cannot read the derivative set", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  data::WriteFileAtomically(path, WithDerivativeCheck(text.str(), check, path.string()));
}

}  // namespace kelvin::sim
