// HDF5 files of named time series and arrays, the format every kelvin stage
// writes. Each dataset carries `units` and `description` attributes; series
// are chunked, gzip-compressed and appendable. Files are written atomically:
// the writer works on a temporary copy and renames it over the target in
// Commit(); an exception or a kill before that leaves the old file intact.
#pragma once

#include <hdf5.h>

#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace kelvin::data {

// Owns one HDF5 identifier and closes it with the matching H5*close.
class H5Handle {
 public:
  H5Handle() = default;
  explicit H5Handle(hid_t id) : id_(id) {}
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  H5Handle(H5Handle&& o) noexcept : id_(o.id_) { o.id_ = H5I_INVALID_HID; }
  H5Handle& operator=(H5Handle&& o) noexcept;
  ~H5Handle() { Reset(); }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void Reset();

 private:
  hid_t id_ = H5I_INVALID_HID;
};

struct Series {
  std::vector<double> values;  // row-major, rows x cols
  std::size_t rows = 0;
  std::size_t cols = 1;
  std::string units;
  std::string description;
  double at(std::size_t row, std::size_t col = 0) const { return values[row * cols + col]; }
};

class H5Writer {
 public:
  enum class Mode { kCreate, kAppend };
  // kCreate starts an empty file; kAppend starts from a copy of the existing
  // target (or an empty file if there is none).
  explicit H5Writer(std::filesystem::path target, Mode mode = Mode::kCreate);
  H5Writer(const H5Writer&) = delete;
  H5Writer& operator=(const H5Writer&) = delete;
  ~H5Writer();

  // Declares an appendable series of `cols` columns (intermediate groups are
  // created). Declaring an existing series with the same width is a no-op.
  void DeclareSeries(const std::string& name, std::string_view units, std::string_view description,
                     std::size_t cols = 1);
  // Appends whole rows (values.size() must be a multiple of the width).
  // Rows are buffered in memory and written in large blocks.
  void Append(const std::string& name, std::span<const double> values);
  // Writes every buffered row to the temporary file.
  void Flush();
  // Writes a fixed array with the given dims (product == values.size()).
  void WriteArray(const std::string& name, std::span<const double> values, std::vector<std::size_t> dims,
                  std::string_view units, std::string_view description);
  void WriteStrings(const std::string& name, const std::vector<std::string>& values,
                    std::string_view description);
  // Attributes on a group or dataset ("/" is the file root); groups are created.
  void SetAttribute(const std::string& object, const std::string& name, std::string_view value);
  void SetAttribute(const std::string& object, const std::string& name, double value);

  // Flushes, closes and renames the temporary file over the target.
  void Commit();
  const std::filesystem::path& target() const { return target_; }

 private:
  hid_t EnsureGroup(const std::string& path);
  hid_t OpenObject(const std::string& path);
  void FlushSeries(const std::string& name, std::vector<double>& buffer);

  static constexpr std::size_t kFlushValues = 1 << 16;
  std::map<std::string, std::vector<double>> pending_;

  std::filesystem::path target_;
  std::filesystem::path tmp_;
  H5Handle file_;
  bool committed_ = false;
};

class H5Reader {
 public:
  explicit H5Reader(std::filesystem::path path);
  bool Has(const std::string& name) const;
  Series Read(const std::string& name) const;
  std::vector<std::string> ReadStrings(const std::string& name) const;
  std::string StringAttribute(const std::string& object, const std::string& name) const;
  double NumberAttribute(const std::string& object, const std::string& name) const;
  bool HasAttribute(const std::string& object, const std::string& name) const;
  // Names of the direct children of a group.
  std::vector<std::string> List(const std::string& group) const;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  H5Handle file_;
};

}  // namespace kelvin::data
