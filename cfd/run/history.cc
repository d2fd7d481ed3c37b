#include "cfd/run/history.h"

#include <limits>

#include "data/schema/errors.h"

namespace kelvin::cfd {

History::Column History::Add(std::string name, std::size_t width, std::string units, std::string what) {
  KELVIN_CHECK(rows_ == 0, "history columns are declared before the first row");
  KELVIN_CHECK(width >= 1, "a column of at least one component");
  for (const Series& s : series_) KELVIN_CHECK(s.name != name, "one history column per name");
  series_.push_back({std::move(name), std::move(units), std::move(what), width, {}});
  return static_cast<Column>(series_.size() - 1);
}

void History::FillRow() {
  for (Series& s : series_) s.values.resize(rows_ * s.width, std::numeric_limits<double>::quiet_NaN());
}

void History::NewRow() {
  FillRow();
  ++rows_;
}

void History::Set(Column column, std::span<const double> values) {
  Series& s = series_.at(static_cast<std::size_t>(column));
  KELVIN_CHECK(rows_ > 0 && values.size() == s.width, "a row started and one value per component");
  s.values.resize((rows_ - 1) * s.width, std::numeric_limits<double>::quiet_NaN());
  s.values.insert(s.values.end(), values.begin(), values.end());
}

void History::Set(Column column, double value) { Set(column, std::span<const double>(&value, 1)); }

void History::Set(Column column, const Vector3& value) { Set(column, std::span<const double>(value.data(), 3)); }

std::span<const double> History::Values(Column column) const {
  const Series& s = series_.at(static_cast<std::size_t>(column));
  return std::span<const double>(s.values).first(std::min(s.values.size(), rows_ * s.width));
}

void History::Write(data::H5Writer& w) const {
  for (const Series& s : series_) {
    std::vector<double> v(s.values.begin(), s.values.begin() + static_cast<std::ptrdiff_t>(
                                                                  std::min(s.values.size(), rows_ * s.width)));
    v.resize(rows_ * s.width, std::numeric_limits<double>::quiet_NaN());
    if (s.width == 1) {
      w.WriteArray(s.name, v, {rows_}, s.units, s.what);
    } else {
      w.WriteArray(s.name, v, {rows_, s.width}, s.units, s.what);
    }
  }
}

}  // namespace kelvin::cfd
