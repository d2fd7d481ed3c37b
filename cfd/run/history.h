// The per-step history of a run by named columns (history.h5): each column
// has a name (the HDF5 dataset path), a width (components per row), units
// and a description; rows are steps. The run driver declares its columns
// (time, Courant number, residuals, patch forces) and every monitor may add
// its own before the time loop.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "cfd/mesh/mesh.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {

class History {
 public:
  using Column = int;

  // Declares a column before the first row; returns its handle.
  Column Add(std::string name, std::size_t width, std::string units, std::string what);
  // Starts a row; every column must be set before the next one (a column
  // left unset holds NaN in that row).
  void NewRow();
  void Set(Column column, double value);
  void Set(Column column, const Vector3& value);
  void Set(Column column, std::span<const double> values);

  std::size_t rows() const { return rows_; }
  // Values of a column, row after row (rows x width).
  std::span<const double> Values(Column column) const;
  // Writes every column as a dataset ({rows} or {rows, width}).
  void Write(data::H5Writer& writer) const;

 private:
  struct Series {
    std::string name, units, what;
    std::size_t width;
    std::vector<double> values;
  };
  void FillRow();
  std::vector<Series> series_;
  std::size_t rows_ = 0;
};

}  // namespace kelvin::cfd
