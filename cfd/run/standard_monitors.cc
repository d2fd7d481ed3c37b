#include "cfd/run/standard_monitors.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <functional>
#include <set>

#include "cfd/parallel/decompose.h"
#include "cfd/parallel/state_layout.h"
#include "cfd/turbulence/turbulence_model.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace fs = std::filesystem;

// --- FieldOutput -------------------------------------------------------------

FieldOutput::FieldOutput(const fs::path& directory, int interval)
    : directory_(directory), interval_(interval), pvd_(directory / "fields.pvd") {}

void FieldOutput::AfterStep(const PimpleSolver& solver, const StepRecord& record, History&) {
  if ((record.last && interval_ >= 0) || (interval_ > 0 && solver.step() % interval_ == 0)) Write(solver);
}

namespace {

// The cell fields written: U, p and what the turbulence model adds.
std::vector<VtuCellData> CellFields(const PimpleSolver& solver) {
  const Mesh& mesh = solver.mesh();
  VtuCellData u{"U", 3, {}}, p{"p", 1, {}};
  for (int i = 0; i < mesh.n_cells(); ++i) {
    for (int k = 0; k < 3; ++k) u.values.push_back(solver.U()[i][k]);
    p.values.push_back(solver.p()[i]);
  }
  std::vector<VtuCellData> cell_data = {u, p};
  if (const TurbulenceModel* t = solver.turbulence()) {
    for (TurbulenceOutput& o : t->CellOutputs()) cell_data.push_back({o.name, o.components, std::move(o.values)});
  }
  return cell_data;
}

// Values on every boundary face: p, U and, under a turbulence model, the
// wall shear stress and y+ (zero off the walls).
std::vector<VtuCellData> BoundaryFields(const PimpleSolver& solver) {
  const int nb = solver.mesh().n_boundary_faces();
  VtuCellData pf{"p", 1, {}}, uf{"U", 3, {}}, tau{"wallShearStress", 3, {}}, yp{"yPlus", 1, {}};
  const TurbulenceModel* t = solver.turbulence();
  for (int b = 0; b < nb; ++b) {
    pf.values.push_back(solver.p().boundary()[b]);
    for (int d = 0; d < 3; ++d) uf.values.push_back(solver.U().boundary()[b][d]);
    if (!t) continue;
    for (int d = 0; d < 3; ++d) tau.values.push_back(t->wall_shear_stress()[b][d]);
    yp.values.push_back(t->y_plus()[b]);
  }
  std::vector<VtuCellData> out = {std::move(pf), std::move(uf)};
  if (t) {
    out.push_back(std::move(tau));
    out.push_back(std::move(yp));
  }
  return out;
}

// Writes `stem`.<extension> in `directory`: serially one file by `write`;
// on ranks each rank's piece stem_r<rank>.<extension> by `write` and, on
// rank 0, the index stem.p<extension> naming them by `index`. Returns the
// file a series lists.
fs::path WriteInPieces(const fs::path& directory, const std::string& stem, const std::string& extension,
                       const DomainPart* part, const std::function<void(const fs::path&)>& write,
                       const std::function<void(const fs::path&, const std::vector<std::string>&)>& index) {
  if (!part) {
    const fs::path file = directory / fmt::format("{}.{}", stem, extension);
    write(file);
    return file;
  }
  std::vector<std::string> pieces;
  for (int r = 0; r < part->size; ++r) pieces.push_back(fmt::format("{}_r{}.{}", stem, r, extension));
  OnEveryRank(part, [&] { write(directory / pieces[part->rank]); });
  const fs::path file = directory / fmt::format("{}.p{}", stem, extension);
  OnFirstRank(part, [&] { index(file, pieces); });
  return file;
}

}  // namespace

// Serially one file per output; on ranks every rank writes its piece (its
// owned cells, its faces of each patch) and rank 0 the index that ParaView
// opens (.pvtu, .pvtp), so no rank holds the whole mesh or gathers a field.
void FieldOutput::Write(const PimpleSolver& solver) {
  const Mesh& mesh = solver.mesh();
  const DomainPart* part = solver.part() && solver.part()->parallel() ? solver.part() : nullptr;
  const std::vector<VtuCellData> cell_data = CellFields(solver);
  const std::vector<VtuCellData> boundary = BoundaryFields(solver);
  const fs::path file = WriteInPieces(
      directory_, fmt::format("fields_{:06d}", solver.step()), "vtu", part,
      [&](const fs::path& f) { WriteVtu(f, mesh, cell_data, part ? part->n_owned : -1); },
      [&](const fs::path& f, const std::vector<std::string>& pieces) { WritePvtu(f, pieces, cell_data); });
  OnFirstRank(part, [&] { pvd_.Add(solver.time(), file); });
  // Surface files, each in a series of its own: the patches whose conditions
  // have their own unknowns (eta), and the turbulence model's walls, with
  // their wall shear stress and first-cell y+ (where the friction comes
  // from, and where the grid leaves the wall treatment's range).
  const TurbulenceModel* t = solver.turbulence();
  std::set<std::string> walls;
  if (t) {
    for (const WallPatchStats& w : t->WallStats()) walls.insert(w.patch);
  }
  const int ni = mesh.n_internal_faces();
  for (int k = 0; k < static_cast<int>(mesh.patches().size()); ++k) {
    const Patch& patch = mesh.patches()[k];
    if (patch.kind == PatchKind::kProcessor) continue;
    // A condition's face fields (the free surface's eta) cover its whole patch on every rank.
    auto fields = solver.p().bc(k).FaceFields();
    const bool wall = walls.count(patch.name) > 0;
    if (fields.empty() && !wall) continue;
    const std::vector<int> index = WholePatchIndices(part, mesh, k);
    std::vector<VtuCellData> data;
    for (auto& [name, values] : fields) {
      std::vector<double> mine(index.size());
      for (std::size_t i = 0; i < index.size(); ++i) mine[i] = values[index[i]];
      data.push_back({name, 1, std::move(mine)});
    }
    for (std::size_t j = 0; j < (wall ? boundary.size() : 2); ++j) {
      const VtuCellData& b = boundary[j];
      const auto first = b.values.begin() + static_cast<long>(patch.start - ni) * b.components;
      data.push_back({b.name, b.components, std::vector<double>(first, first + patch.size * b.components)});
    }
    const fs::path surface_file = WriteInPieces(
        directory_, fmt::format("{}_{:06d}", patch.name, solver.step()), "vtp", part,
        [&](const fs::path& f) { WritePatchVtp(f, mesh, patch, data); },
        [&](const fs::path& f, const std::vector<std::string>& pieces) { WritePvtp(f, pieces, data); });
    OnFirstRank(part, [&] {
      auto [series, inserted] = surfaces_.try_emplace(patch.name, directory_ / (patch.name + ".pvd"));
      series->second.Add(solver.time(), surface_file);
    });
  }
}

// --- TurbulenceReport --------------------------------------------------------

void TurbulenceReport::Start(PimpleSolver& solver, History& h, const RunStart&) {
  const TurbulenceModel* t = solver.turbulence();
  if (!t) return;
  res_k_ = h.Add("turbulence/residuals/k", 1, "1", "initial normalized residual of k");
  res_omega_ = h.Add("turbulence/residuals/omega", 1, "1", "initial normalized residual of omega");
  bounded_k_ = h.Add("turbulence/bounded/k", 1, "1", "cells the bound step lifted to the floor (k)");
  bounded_omega_ = h.Add("turbulence/bounded/omega", 1, "1", "cells the bound step lifted to the floor (omega)");
  for (const WallPatchStats& w : t->WallStats()) {
    y_plus_.push_back(h.Add("turbulence/y_plus/" + w.patch, 3, "1",
                            "first-cell y+ on the wall patch: min, area-weighted mean, max"));
  }
}

void TurbulenceReport::AfterStep(const PimpleSolver& solver, const StepRecord& record, History& h) {
  const TurbulenceModel* t = solver.turbulence();
  if (!t) return;
  const TurbulenceSummary& ts = solver.turbulence_summary();
  h.Set(res_k_, ts.initial_residual_k);
  h.Set(res_omega_, ts.initial_residual_omega);
  h.Set(bounded_k_, static_cast<double>(ts.bounded_k));
  h.Set(bounded_omega_, static_cast<double>(ts.bounded_omega));
  last_ = t->WallStats();
  for (std::size_t k = 0; k < last_.size() && k < y_plus_.size(); ++k) {
    h.Set(y_plus_[k], Vector3(last_[k].y_plus_min, last_[k].y_plus_mean, last_[k].y_plus_max));
  }
  if (ts.bounded_k + ts.bounded_omega > 0) {
    spdlog::warn("step {}: the bound step lifted {} k and {} omega cells to the floor", record.step.step,
                 ts.bounded_k, ts.bounded_omega);
  }
}

std::vector<std::string> TurbulenceReport::Finish(const PimpleSolver&) {
  std::vector<std::string> lines;
  for (const WallPatchStats& w : last_) {
    lines.push_back(fmt::format("y+ on {}: min {:.3g}, mean {:.3g}, max {:.3g}", w.patch, w.y_plus_min,
                                w.y_plus_mean, w.y_plus_max));
    lines.push_back(YPlusDistribution(w));
    const std::string warning = YPlusWarning(w);
    if (!warning.empty()) {
      spdlog::warn("{}", warning);
      lines.push_back(warning);
    }
  }
  return lines;
}

// --- ForceCoefficients -------------------------------------------------------

ForceCoefficients::ForceCoefficients(const Case& c)
    : patches_(c.force_patches), reference_(c.settings.reference), rho_(c.settings.rho) {}

void ForceCoefficients::Start(PimpleSolver&, History& h, const RunStart&) {
  columns_[0] = h.Add("resistance/C_T", 1, "1", "total resistance coefficient F.d / (rho U^2 S / 2) of the force patches");
  columns_[1] = h.Add("resistance/C_F", 1, "1", "viscous (friction) part of C_T");
  columns_[2] = h.Add("resistance/C_P", 1, "1", "pressure part of C_T");
}

void ForceCoefficients::AfterStep(const PimpleSolver&, const StepRecord& record, History& h) {
  const PatchForce f = record.forces.Sum(patches_);
  const double q = 0.5 * rho_ * reference_.speed * reference_.speed * reference_.area;
  const double cp = f.pressure.dot(reference_.direction) / q, cf = f.viscous.dot(reference_.direction) / q;
  last_[0] = cp + cf;
  last_[1] = cf;
  last_[2] = cp;
  for (int j = 0; j < 3; ++j) h.Set(columns_[j], last_[j]);
}

void ForceCoefficients::WriteHistory(data::H5Writer& w) const {
  w.WriteArray("resistance/reference", std::vector<double>{reference_.speed, reference_.area, rho_}, {3},
               "m/s, m^2, kg/m^3", "reference speed U, area S and density rho of the coefficients");
}

std::vector<std::string> ForceCoefficients::Finish(const PimpleSolver&) {
  return {fmt::format("resistance: C_T {:.5e} = C_F {:.5e} + C_P {:.5e} (U {:.4g} m/s, S {:.5g} m^2)", last_[0],
                      last_[1], last_[2], reference_.speed, reference_.area)};
}

}  // namespace kelvin::cfd
