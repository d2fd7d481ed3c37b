#include "data/schema/appendage_runs.h"

#include <fmt/format.h>

#include <cmath>

#include "data/schema/errors.h"
#include "data/schema/h5_file.h"

namespace kelvin::data {
namespace {

constexpr const char* kGroup = "/appendages";
constexpr std::size_t kCols = kAppendageColumns.size();

std::array<double, kCols> Row(const AppendageRun& r) {
  return {r.u, r.v, r.r, r.delta, r.n, r.X, r.Y, r.N, r.T, r.U_A, r.J, r.K_T, r.F_N, r.u_R, r.v_R, 0.0};
}

AppendageRun FromRow(const Series& s, std::size_t i, std::string name) {
  AppendageRun r;
  r.name = std::move(name);
  double* fields[] = {&r.u, &r.v, &r.r, &r.delta, &r.n, &r.X, &r.Y, &r.N, &r.T, &r.U_A, &r.J, &r.K_T,
                      &r.F_N, &r.u_R, &r.v_R};
  for (std::size_t k = 0; k < std::size(fields); ++k) *fields[k] = s.at(i, k);
  return r;
}

AppendageGeometry ReadGeometry(const H5Reader& h, const std::string& file) {
  for (const char* name : {"Lpp", "D_p", "A_R", "H_R", "x_R_prime", "x_P_prime", "rho", "ship_file"}) {
    if (!h.HasAttribute(kGroup, name)) {
      throw DataFileError(fmt::format("{}: {} has no attribute '{}'; expected the ship file's propeller and rudder",
                                      file, kGroup, name));
    }
  }
  AppendageGeometry g;
  g.Lpp = h.NumberAttribute(kGroup, "Lpp");
  g.D_p = h.NumberAttribute(kGroup, "D_p");
  g.A_R = h.NumberAttribute(kGroup, "A_R");
  g.H_R = h.NumberAttribute(kGroup, "H_R");
  g.rho = h.NumberAttribute(kGroup, "rho");
  g.x_R_prime = h.NumberAttribute(kGroup, "x_R_prime");
  g.x_P_prime = h.NumberAttribute(kGroup, "x_P_prime");
  g.ship_file = h.StringAttribute(kGroup, "ship_file");
  for (auto [name, value] :
       {std::pair{"Lpp", g.Lpp}, {"D_p", g.D_p}, {"A_R", g.A_R}, {"H_R", g.H_R}, {"rho", g.rho}}) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw DataFileError(fmt::format("{}: {} attribute {} = {}: expected a positive number", file, kGroup, name, value));
    }
  }
  return g;
}

}  // namespace

std::vector<AppendageTest> PlanAppendageTests(const AppendageDesign& d, double U, double Lpp) {
  std::vector<AppendageTest> out;
  const double n = d.propeller_rate, deg = 180.0 / M_PI;
  out.push_back({"prop_straight", U, 0, 0, 0, n});
  for (double f : d.rate_factors) out.push_back({fmt::format("prop_rate_x{:.3f}", f), U, 0, 0, 0, f * n});
  for (double a : d.rudder_angles) out.push_back({fmt::format("prop_rudder_{:+.1f}deg", a * deg), U, 0, 0, a, n});
  for (double b : d.drift_angles) {
    out.push_back({fmt::format("prop_drift_{:+.1f}deg", b * deg), U * std::cos(b), -U * std::sin(b), 0, 0, n});
  }
  for (const auto& c : d.circular) {
    std::string name = fmt::format("prop_circular_{:+.1f}deg_r{:.3f}", c.beta * deg, c.r_prime);
    if (c.rate_factor != 1.0) name += fmt::format("_x{:.3f}", c.rate_factor);
    out.push_back({name, U * std::cos(c.beta), -U * std::sin(c.beta), c.r_prime * U / Lpp, 0, c.rate_factor * n});
  }
  return out;
}

void WriteAppendageRuns(const AppendageCampaign& c, H5Writer& w) {
  std::vector<double> values;
  std::vector<std::string> names;
  for (const AppendageRun& r : c.runs) {
    const auto row = Row(r);
    values.insert(values.end(), row.begin(), row.end());
    names.push_back(r.name);
  }
  w.WriteArray(std::string(kGroup) + "/runs", values, {c.runs.size(), kCols},
               "m/s, m/s, rad/s, rad, 1/s, N, N, N m, N, m/s, 1, 1, N, m/s, m/s, -",
               fmt::format("captive runs with the propeller and rudder, means over the settled window; columns {}",
                           fmt::join(kAppendageColumns, ", ")));
  w.WriteStrings(std::string(kGroup) + "/names", names, "run names, one per row of runs");
  const AppendageGeometry& g = c.geometry;
  w.SetAttribute(kGroup, "Lpp", g.Lpp);
  w.SetAttribute(kGroup, "D_p", g.D_p);
  w.SetAttribute(kGroup, "A_R", g.A_R);
  w.SetAttribute(kGroup, "H_R", g.H_R);
  w.SetAttribute(kGroup, "rho", g.rho);
  w.SetAttribute(kGroup, "x_R_prime", g.x_R_prime);
  w.SetAttribute(kGroup, "x_P_prime", g.x_P_prime);
  w.SetAttribute(kGroup, "ship_file", g.ship_file);
}

bool HasAppendageRuns(const std::filesystem::path& path) { return H5Reader(path).Has(std::string(kGroup) + "/runs"); }

AppendageCampaign ReadAppendageRuns(const std::filesystem::path& path, bool geometry) {
  const H5Reader h(path);
  const std::string file = path.string();
  AppendageCampaign c;
  if (geometry) c.geometry = ReadGeometry(h, file);
  const Series s = h.Read(std::string(kGroup) + "/runs");
  const std::vector<std::string> names = h.ReadStrings(std::string(kGroup) + "/names");
  if (s.cols != kCols || names.size() != s.rows) {
    throw DataFileError(fmt::format("{}: {}/runs is {} x {} with {} names; expected {} columns and one name per row",
                                    file, kGroup, s.rows, s.cols, names.size(), kCols));
  }
  for (std::size_t i = 0; i < s.rows; ++i) {
    for (std::size_t k = 0; k + 1 < kCols; ++k) {
      if (!std::isfinite(s.at(i, k))) {
        throw DataFileError(fmt::format("{}: appendage run '{}': {} = {}: expected a finite number", file, names[i],
                                        kAppendageColumns[k], s.at(i, k)));
      }
    }
    c.runs.push_back(FromRow(s, i, names[i]));
  }
  return c;
}

}  // namespace kelvin::data
