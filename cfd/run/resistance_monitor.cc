#include "cfd/run/resistance_monitor.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/freesurface/wave_analysis.h"
#include "cfd/parallel/state_layout.h"
#include "data/reference/friction_lines.h"
#include "data/schema/errors.h"
#include "data/schema/file_status.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {

// Per hull face at the last step: where on the hull the resistance acts. On
// MPI ranks every rank's faces, in the whole mesh's order (collective).
struct HullFaces {
  std::vector<Vector3> centre, area, pressure, viscous;
};

ResistanceMonitor::ResistanceMonitor(const Case& c)
    : options_(c.settings.resistance.value()),
      reference_(c.settings.reference),
      rho_(c.settings.rho),
      nu_(c.settings.nu),
      file_(c.settings.output.directory / "resistance.h5"),
      free_surface_(options_.free_surface_patch.empty() ? nullptr : c.free_surface),
      hull_(c.mesh->FindPatch(options_.hull_patch)),
      flow_through_(FlowThroughTime(*c.mesh, c.settings.reference, c.part.get())),
      tolerance_(c.settings.time.steady ? c.settings.time.steady->criterion.tolerance
                                        : std::numeric_limits<double>::quiet_NaN()) {
  KELVIN_CHECK(hull_ >= 0, "a hull patch the loader resolved");
  if (free_surface_) g_ = free_surface_->options().g;
  turbulent_ = c.solver->turbulence() != nullptr;
  steady_.window = c.settings.time.steady ? c.settings.time.steady->criterion.window : 0.0;
  steady_.release_time = std::numeric_limits<double>::quiet_NaN();
}

void ResistanceMonitor::AfterStep(const PimpleSolver& solver, const StepRecord& record, History&) {
  const PatchForce f = record.forces.Sum(hull_);
  const double rp = f.pressure.dot(reference_.direction), rf = f.viscous.dot(reference_.direction);
  double rwl = 0.0;
  if (free_surface_) {
    rwl = WaterlineForce(free_surface_->surface(), free_surface_->eta(), hull_, rho_, g_).dot(reference_.direction);
  }
  steady_ = record.steady;
  if (record.last) last_faces_ = record.forces.Faces(hull_);  // the report's hull faces
  rows_.push_back({solver.time(), rp + rf, rf, rp, rwl, steady_.force_change, steady_.eta_change});
}


namespace {

// A warning line of the report: logged now, and returned as its own line of the summary.
std::string LoudLine(const std::string& warning) {
  spdlog::warn("{}", warning);
  return "\n  " + warning;
}

void Scalar(data::H5Writer& w, const std::string& name, double v, std::string_view units, std::string_view what) {
  w.WriteArray(name, std::span<const double>(&v, 1), {1}, units, what);
}

// Vectors of one patch's faces as an {n, 3} array.
std::vector<double> Flatten(std::span<const Vector3> v) {
  std::vector<double> out(3 * v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (int d = 0; d < 3; ++d) out[3 * i + d] = v[i][d];
  }
  return out;
}

HullFaces GatherHullFaces(const PimpleSolver& solver, int hull, const PatchFaceForces& ff) {
  const Mesh& mesh = solver.mesh();
  const Patch& patch = mesh.patches()[hull];
  const auto gather = [&](std::span<const Vector3> v) { return GatherPatchFaces(solver.part(), mesh, hull, v); };
  const auto slice = [&](std::span<const Vector3> all) {
    return all.subspan(static_cast<std::size_t>(patch.start), static_cast<std::size_t>(patch.size));
  };
  return {gather(slice(mesh.face_centres())), gather(slice(mesh.face_areas())), gather(ff.pressure),
          gather(ff.viscous)};
}

void WriteHullFaces(data::H5Writer& w, const HullFaces& hf, const Vector3& direction) {
  const std::size_t n = hf.centre.size();
  w.WriteArray("hull_faces/centre", Flatten(hf.centre), {n, 3}, "m", "hull face centres (mesh axes)");
  w.WriteArray("hull_faces/area", Flatten(hf.area), {n, 3}, "m^2",
               "hull face area vectors, out of the water into the hull");
  w.WriteArray("hull_faces/pressure_force", Flatten(hf.pressure), {n, 3}, "N",
               "pressure force of the water on each hull face");
  w.WriteArray("hull_faces/viscous_force", Flatten(hf.viscous), {n, 3}, "N",
               "viscous force of the water on each hull face");
  w.WriteArray("hull_faces/direction", std::vector<double>{direction.x(), direction.y(), direction.z()}, {3}, "1",
               "unit resistance direction d (R = F . d)");
}

// The wave profile along the hull, the wave cuts and the whole pattern, face by face.
void WriteWaves(data::H5Writer& w, const LinearizedFreeSurface& fs, int hull, const ResistanceOptions& o) {
  const PatchSurface& s = fs.surface();
  const std::vector<double>& eta = fs.eta();
  const WaveProfile prof = HullWaveProfile(s, eta, hull);
  const std::size_t m = prof.x.size();
  w.WriteArray("wave_profile/x", prof.x, {m}, "m", "waterline edge centre x (port y >= 0 first, then starboard)");
  w.WriteArray("wave_profile/y", prof.y, {m}, "m", "waterline edge centre y");
  w.WriteArray("wave_profile/eta", prof.eta, {m}, "m", "wave elevation at the hull");
  const int np = o.wave_cut_points;
  std::vector<double> x(np);
  for (int k = 0; k < np; ++k) x[k] = s.min().x() + (s.max().x() - s.min().x()) * (k + 0.5) / np;
  for (std::size_t c = 0; c < o.wave_cut_y.size(); ++c) {
    const double y0 = o.wave_cut_y[c];
    const std::string grp = fmt::format("wave_cuts/cut{}", c);
    w.WriteArray(grp + "/x", x, {x.size()}, "m", "stations along the cut");
    w.WriteArray(grp + "/eta", WaveCut(s, eta, y0, x), {x.size()}, "m", "wave elevation (NaN outside the patch)");
    w.SetAttribute(grp, "y", y0);
  }
  const std::size_t nf = eta.size();
  std::vector<double> fx(nf), fy(nf);
  for (std::size_t i = 0; i < nf; ++i) {
    fx[i] = s.centres()[i].x();
    fy[i] = s.centres()[i].y();
  }
  w.WriteArray("surface/x", fx, {nf}, "m", "free-surface face centre x");
  w.WriteArray("surface/y", fy, {nf}, "m", "free-surface face centre y");
  w.WriteArray("surface/area", s.areas(), {nf}, "m^2", "free-surface face area");
  w.WriteArray("surface/eta", eta, {nf}, "m", "wave elevation");
  w.WriteArray("surface/damping", fs.damping(), {nf}, "1/s", "beach damping rate (0 outside the beaches)");
  Scalar(w, "eta_max", *std::max_element(eta.begin(), eta.end()), "m", "largest wave elevation on the patch");
  Scalar(w, "eta_min", *std::min_element(eta.begin(), eta.end()), "m", "lowest wave elevation on the patch");
}

}  // namespace

std::string ResistanceMonitor::WriteSplit(data::H5Writer& w) const {
  const auto& last = rows_.back();
  const double q = DynamicForce();
  const double rt = last[1], rf = last[2], rp = last[3];
  Scalar(w, "speed", reference_.speed, "m/s", "inflow speed U");
  Scalar(w, "rho", rho_, "kg/m^3", "density");
  Scalar(w, "wetted_area", reference_.area, "m^2", "wetted area at rest S (hull patch below z = 0)");
  Scalar(w, "R_T", rt, "N", "total resistance R_F + R_P along the inflow direction");
  Scalar(w, "R_F", rf, "N", "friction (wall shear) resistance");
  Scalar(w, "R_P", rp, "N", "pressure resistance");
  Scalar(w, "C_T", rt / q, "1", "R_T / (0.5 rho S U^2)");
  Scalar(w, "C_F", rf / q, "1", "R_F / (0.5 rho S U^2)");
  Scalar(w, "C_P", rp / q, "1", "R_P / (0.5 rho S U^2)");
  Scalar(w, "converged", steady_.settled ? 1.0 : 0.0, "1", "1 if the steady criterion stopped the run");
  Scalar(w, "converged_step", steady_.settled_step, "1", "step at which the criterion was met (-1: not met)");
  Scalar(w, "tolerance", tolerance_, "1", "relative change allowed over one window");
  Scalar(w, "window", steady_.window, "s", "pseudo-time window of the criterion (one flow-through)");
  Scalar(w, "flow_through", flow_through_, "s", "mesh extent along the inflow / U");
  Scalar(w, "release_time", steady_.release_time, "s",
         "pseudo-time at which the rigid lid was released (NaN: never held)");
  std::string summary = fmt::format(
      "resistance on '{}': R_T = {:.5g} N (R_F {:.5g}, R_P {:.5g}); C_T = {:.5e}, C_F = {:.5e}, C_P = {:.5e} "
      "(S = {:.5g} m^2, U = {:.5g} m/s); {} (force change {:.2e}, eta change {:.2e} over {:.4g} s)",
      options_.hull_patch, rt, rf, rp, rt / q, rf / q, rp / q, reference_.area, reference_.speed,
      steady_.settled ? fmt::format("converged at step {}", steady_.settled_step) : std::string("NOT converged"),
      steady_.force_change, steady_.eta_change, steady_.window);
  if (reference_.length > 0.0) {
    const double fn = reference_.speed / std::sqrt(g_ * reference_.length);
    Scalar(w, "Fn", fn, "1", "Froude number U / sqrt(g L)");
    summary += fmt::format("; Fn = {:.4f}", fn);
    if (nu_ > 0.0) {
      const double re = reference_.speed * reference_.length / nu_;
      Scalar(w, "Re", re, "1", "Reynolds number U L / nu");
      summary += fmt::format(", Re = {:.4g}", re);
      if (turbulent_) {
        // A turbulent hull's friction lies near the ITTC-57 line (CFD and
        // model tests give about 1.0 to 1.1 of it); well outside, R_F and
        // what is built on it are wrong, usually through the wall cells.
        const double ratio = FrictionRatio();
        Scalar(w, "C_F_over_ITTC57", ratio, "1", "C_F / C_F0, C_F0 = 0.075 / (log10 Re - 2)^2 (ITTC 1957)");
        summary += fmt::format("; C_F / C_F0(ITTC-57) = {:.3f}", ratio);
      }
    }
  }
  return summary;
}

std::string ResistanceMonitor::WriteWaveMaking(data::H5Writer& w) const {
  if (options_.double_body.empty()) return "";
  if (!data::PathExists(options_.double_body)) {
    return fmt::format("; no wave-making part: the double-body result {} does not exist (run it first)",
                       options_.double_body.string());
  }
  // The wave-making part by coefficients, C_W = C_P - C_P(double body), so
  // a double-body run at another speed of the same grid serves (C_P of the
  // double body changes only through the Reynolds number).
  const double q = DynamicForce();
  const double rp = rows_.back()[3];
  const data::H5Reader db(options_.double_body);
  const double cp_db = db.Read("C_P").at(0);
  const double s_db = db.Read("wetted_area").at(0), u_db = db.Read("speed").at(0);
  if (std::abs(s_db - reference_.area) > 1e-6 * reference_.area) {
    throw DataFileError(fmt::format("double_body {}: wetted area {} m^2; expected the same grid as this run ({} m^2)",
                                    options_.double_body.string(), s_db, reference_.area));
  }
  Scalar(w, "C_P_double_body", cp_db, "1", "pressure resistance coefficient of the double-body run on the same grid");
  Scalar(w, "double_body_speed", u_db, "m/s", "speed of that double-body run");
  const double cw = rp / q - cp_db, rw = cw * q;
  Scalar(w, "C_W", cw, "1", "wave-making part C_P - C_P(double body)");
  Scalar(w, "R_W", rw, "N", "wave-making resistance C_W 0.5 rho S U^2");
  return fmt::format("; wave-making C_W = C_P - C_P(double body at {:.4g} m/s) = {:.5e} (R_W = {:.5g} N)", u_db,
                     cw, rw) +
         NegativeWavePartWarning(rw, rows_.back()[1]);
}

std::string ResistanceMonitor::LinearizationHint() const {
  using L = LinearizedFreeSurfaceOptions::Linearization;
  if (!free_surface_) return "this run has no free surface: is double_body the run meant?";
  if (free_surface_->options().linearization == L::kUniformStream) {
    return "linearization uniform_stream: the Neumann-Kelvin condition raises a spurious crest over a shallow "
           "stern run; compare linearization local_flow";
  }
  return "linearization local_flow: check the unresolved-steps warning and the surface fields base_flow and "
         "base_flow_gain";
}

std::string ResistanceMonitor::NegativeWavePartWarning(double r_w, double r_t) const {
  const double resolution = (std::isfinite(tolerance_) ? tolerance_ : 1e-3) * std::abs(r_t);
  if (!(r_w < -resolution)) return "";
  const std::string warning = fmt::format(
      "WARNING: the free surface lowered the pressure resistance by {:.4g} N against the double body on the same "
      "grid ({:.2g}% of R_T): the waves of a ship in steady motion carry energy away, so their resistance is positive. This wave part is an "
      "error of the free-surface condition on this hull or grid ({}; docs/formulation.md sections 3.1 and 5.3), "
      "and R_T is low by at least as much",
      -r_w, -100.0 * r_w / std::abs(r_t), LinearizationHint());
  return LoudLine(warning);
}

std::vector<std::string> ResistanceMonitor::Finish(const PimpleSolver& solver) {
  KELVIN_CHECK(!rows_.empty() && static_cast<int>(last_faces_.pressure.size()) == solver.mesh().patches()[hull_].size,
               "a recorded last step before the report");
  const HullFaces faces = GatherHullFaces(solver, hull_, last_faces_);
  std::string summary;
  OnFirstRank(solver.part(), [&] { summary = Write(file_, faces); });
  return {FromFirstRank(solver.part(), std::move(summary))};
}

std::string ResistanceMonitor::Write(const std::filesystem::path& file, const HullFaces& faces) const {
  data::H5Writer w(file);
  std::string summary = WriteSplit(w);
  summary += WriteWaveMaking(w);
  const std::size_t rows = rows_.size();
  std::vector<double> h(rows * 7);
  for (std::size_t r = 0; r < rows; ++r) std::copy(rows_[r].begin(), rows_[r].end(), h.begin() + 7 * r);
  w.WriteArray("history", h, {rows, 7}, "s, N, N, N, N, 1, 1",
               "per step: time, R_T, R_F, R_P, R_WL, force change, eta change (NaN before a full window)");
  WriteHullFaces(w, faces, reference_.direction);
  if (free_surface_) {
    const double q = DynamicForce();
    const double rwl = rows_.back()[4];
    Scalar(w, "R_WL", rwl, "N", "waterline-integral correction 0.5 rho g sum eta^2 n_x dl (not in R_T)");
    Scalar(w, "C_WL", rwl / q, "1", "R_WL / (0.5 rho S U^2)");
    summary += fmt::format("; waterline correction (separate) R_WL = {:.4g} N, C_WL = {:.3e}", rwl, rwl / q);
    WriteWaves(w, *free_surface_, hull_, options_);
    summary += UnresolvedStepsWarning(w);
  }
  w.Commit();
  return summary + FrictionWarning();
}

std::string ResistanceMonitor::UnresolvedStepsWarning(data::H5Writer& w) const {
  if (!(reference_.speed > 0.0)) return "";
  const double jump = reference_.speed * reference_.speed / (4.0 * g_);
  const std::vector<int> faces = free_surface_->UnresolvedSteps(jump);
  Scalar(w, "unresolved_steps", static_cast<double>(faces.size()), "1",
         "surface faces whose eta steps from a neighbour's by more than U^2 / 4g");
  if (faces.empty()) return "";
  int worst = faces[0];
  const std::vector<double>& eta = free_surface_->eta();
  for (int i : faces) {
    if (std::abs(eta[i]) > std::abs(eta[worst])) worst = i;
  }
  const Vector3& x = free_surface_->surface().centres()[worst];
  const std::string warning = fmt::format(
      "WARNING: the elevation of {} free-surface face(s) steps from a neighbour's by more than U^2/4g = {:.3g} m "
      "(eta {:.3g} m at ({:.4g}, {:.4g}) m): that is not a wave the surface mesh resolves, and R_P, R_T carry its "
      "pressure; with linearization local_flow compare the surface field base_flow_gain there "
      "(docs/formulation.md section 3.1)",
      faces.size(), jump, eta[worst], x.x(), x.y());
  return LoudLine(warning);
}

std::string ResistanceMonitor::FrictionWarning() const {
  if (!turbulent_ || !(reference_.length > 0.0) || !(nu_ > 0.0)) return "";
  const double ratio = FrictionRatio();
  if (ratio >= kFrictionLow && ratio <= kFrictionHigh) return "";
  const std::string warning = fmt::format(
      "WARNING: the friction on '{}' is {:.2f} of the ITTC-57 line at Re = {:.3g} (a turbulent hull gives about "
      "1.0-1.1; outside [{}, {}] it is not a hull's boundary layer): R_F, R_T and what is built on them are off; "
      "check the hull y+ and the prism layers of the grid",
      options_.hull_patch, ratio, reference_.speed * reference_.length / nu_, kFrictionLow, kFrictionHigh);
  return LoudLine(warning);
}

double ResistanceMonitor::FrictionRatio() const {
  const double re = reference_.speed * reference_.length / nu_;
  return rows_.back()[2] / DynamicForce() / data::Ittc57FrictionCoefficient(re);
}

}  // namespace kelvin::cfd
