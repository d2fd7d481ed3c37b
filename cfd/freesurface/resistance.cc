#include "cfd/freesurface/resistance.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "cfd/motion/ship_forces.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// eta at the centre of edge e of the face `face`, from the face value and
// its least-squares gradient (the face value where it has none).
double EdgeElevation(const PatchSurface& s, std::span<const double> eta, const std::vector<Vector3>& grad, int face,
                     const Vector3& point) {
  if (!s.valid_gradient(face)) return eta[face];
  return eta[face] + grad[face].dot(point - s.centres()[face]);
}
}  // namespace

SteadyConvergence::SteadyConvergence(double window, double tolerance, int min_steps)
    : window_(window), tolerance_(tolerance), min_steps_(min_steps), force_change_(kNaN), eta_change_(kNaN) {
  if (min_steps < 1) throw ConfigError(fmt::format("window_steps = {}; expected >= 1", min_steps));
  if (!(window > 0.0) || !std::isfinite(window)) {
    throw ConfigError(fmt::format("convergence window = {} s; expected > 0", window));
  }
  if (!(tolerance > 0.0 && tolerance < 1.0)) {
    throw ConfigError(fmt::format("convergence tolerance = {}; expected a relative change in (0, 1)", tolerance));
  }
}

void SteadyConvergence::Add(double time, std::span<const double> forces, std::span<const double> eta) {
  KELVIN_CHECK(!forces.empty(), "at least the total resistance is monitored");
  samples_.push_back({time, {forces.begin(), forces.end()}, {eta.begin(), eta.end()}});
  // Keep the newest sample that is at least one window old, and all later ones.
  while (samples_.size() > static_cast<std::size_t>(min_steps_) + 1 && samples_[1].time <= time - window_) {
    samples_.pop_front();
  }
  force_change_ = eta_change_ = kNaN;
  if (samples_.front().time > time - window_ * (1.0 - 1e-9)) return;
  if (samples_.size() < static_cast<std::size_t>(min_steps_) + 1) return;
  const Sample& now = samples_.back();
  const double scale = std::abs(now.forces[0]);
  double eta_norm = 0.0;
  for (double e : now.eta) eta_norm += e * e;
  eta_norm = std::sqrt(eta_norm);
  double df = 0.0, de = 0.0;
  for (const Sample& s : samples_) {
    KELVIN_CHECK(s.forces.size() == now.forces.size() && s.eta.size() == now.eta.size(), "same monitored sizes");
    for (std::size_t k = 0; k < s.forces.size(); ++k) df = std::max(df, std::abs(s.forces[k] - now.forces[k]));
    double d2 = 0.0;
    for (std::size_t i = 0; i < s.eta.size(); ++i) d2 += (s.eta[i] - now.eta[i]) * (s.eta[i] - now.eta[i]);
    de = std::max(de, std::sqrt(d2));
  }
  force_change_ = scale > 0.0 ? df / scale : (df > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  eta_change_ = now.eta.empty() ? 0.0 : (eta_norm > 0.0 ? de / eta_norm : (de > 0.0 ? 1.0 : 0.0));
}

bool SteadyConvergence::Converged() const {
  return std::isfinite(force_change_) && std::isfinite(eta_change_) && force_change_ < tolerance_ &&
         eta_change_ < tolerance_;
}

std::vector<double> WaveCut(const PatchSurface& surface, std::span<const double> eta, double y0,
                            std::span<const double> x) {
  KELVIN_CHECK(static_cast<int>(eta.size()) == surface.size(), "one elevation per patch face");
  std::vector<Vector3> grad;
  surface.Gradient(eta, grad);
  const auto& edges = surface.edges();
  // Radius of each face about its centre (edge centres bound it for convex faces).
  const int n = surface.size();
  std::vector<double> radius(n, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int e : surface.face_edges(i)) {
      const double len = edges[e].normal.norm();
      radius[i] = std::max(radius[i], (edges[e].centre - surface.centres()[i]).norm() + 0.5 * len);
    }
  }
  std::vector<double> out(x.size(), kNaN);
  for (std::size_t k = 0; k < x.size(); ++k) {
    const Vector3 p(x[k], y0, 0.0);
    for (int i = 0; i < n; ++i) {
      if ((p - surface.centres()[i]).head<2>().norm() > radius[i]) continue;
      bool inside = true;
      for (int e : surface.face_edges(i)) {
        // Outward normal of face i across edge e.
        const Vector3 nrm = edges[e].face == i ? edges[e].normal : Vector3(-edges[e].normal);
        if ((p - edges[e].centre).dot(nrm) > 1e-12 * nrm.norm()) {
          inside = false;
          break;
        }
      }
      if (!inside) continue;
      out[k] = surface.valid_gradient(i) ? eta[i] + grad[i].dot(p - surface.centres()[i]) : eta[i];
      break;
    }
  }
  return out;
}

WaveProfile HullWaveProfile(const PatchSurface& surface, std::span<const double> eta, int hull_patch) {
  KELVIN_CHECK(static_cast<int>(eta.size()) == surface.size(), "one elevation per patch face");
  std::vector<Vector3> grad;
  surface.Gradient(eta, grad);
  struct Point {
    double x, y, eta;
  };
  std::vector<Point> points;
  for (const auto& e : surface.edges()) {
    if (e.neighbour >= 0 || e.rim_patch != hull_patch) continue;
    points.push_back({e.centre.x(), e.centre.y(), EdgeElevation(surface, eta, grad, e.face, e.centre)});
  }
  std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) {
    const bool pa = a.y >= 0.0, pb = b.y >= 0.0;
    return pa != pb ? pb : a.x < b.x;
  });
  WaveProfile w;
  for (const Point& p : points) {
    w.x.push_back(p.x);
    w.y.push_back(p.y);
    w.eta.push_back(p.eta);
  }
  return w;
}

Vector3 WaterlineForce(const PatchSurface& surface, std::span<const double> eta, int hull_patch, double rho,
                       double g) {
  KELVIN_CHECK(static_cast<int>(eta.size()) == surface.size(), "one elevation per patch face");
  std::vector<Vector3> grad;
  surface.Gradient(eta, grad);
  Vector3 f = Vector3::Zero();
  for (const auto& e : surface.edges()) {
    if (e.neighbour >= 0 || e.rim_patch != hull_patch) continue;
    const double h = EdgeElevation(surface, eta, grad, e.face, e.centre);
    f += 0.5 * rho * g * h * h * e.normal;
  }
  return f;
}

ResistanceMonitor::ResistanceMonitor(const PimpleSolver& solver, ResistanceOptions options)
    : options_(std::move(options)) {
  const Mesh& mesh = solver.mesh();
  hull_ = mesh.FindPatch(options_.hull_patch);
  if (hull_ < 0) throw ConfigError(fmt::format("hull: no patch '{}' in the mesh", options_.hull_patch));
  if (!options_.free_surface_patch.empty()) {
    free_surface_ = mesh.FindPatch(options_.free_surface_patch);
    if (free_surface_ < 0 || !dynamic_cast<const LinearizedFreeSurface*>(&solver.p().bc(free_surface_))) {
      throw ConfigError(fmt::format("free_surface: '{}' is not a patch with a linearizedFreeSurface pressure",
                                    options_.free_surface_patch));
    }
  }
  speed_ = options_.inflow.norm();
  if (!(speed_ > 0.0) || !std::isfinite(speed_)) {
    throw ConfigError(fmt::format("inflow: speed {} m/s; expected a non-zero inflow velocity [u, v, w]", speed_));
  }
  direction_ = options_.inflow / speed_;
  if (!(options_.rho > 0.0)) throw ConfigError(fmt::format("rho = {}; expected > 0 kg/m^3", options_.rho));
  area_ = options_.wetted_area;
  if (area_ <= 0.0) {
    const Patch& p = mesh.patches()[hull_];
    for (int f = p.start; f < p.start + p.size; ++f) area_ += mesh.face_area_magnitudes()[f];
  }
  if (options_.wave_cut_points < 2) {
    throw ConfigError(fmt::format("wave_cut_points = {}; expected >= 2", options_.wave_cut_points));
  }
  // One flow-through: the extent of the mesh along the inflow direction.
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (const Vector3& x : mesh.points()) {
    lo = std::min(lo, x.dot(direction_));
    hi = std::max(hi, x.dot(direction_));
  }
  flow_through_ = (hi - lo) / speed_;
  const double window = options_.window > 0.0 ? options_.window : flow_through_;
  convergence_.emplace(window, options_.tolerance, options_.window_steps);
  if (!(options_.min_windows >= 1.0)) {
    throw ConfigError(fmt::format("min_windows = {}; expected >= 1", options_.min_windows));
  }
  if (options_.ramp_steps < 0) throw ConfigError(fmt::format("ramp_steps = {}; expected >= 0", options_.ramp_steps));
  if (!(options_.rigid_lid_windows >= 0.0) || !std::isfinite(options_.rigid_lid_windows)) {
    throw ConfigError(fmt::format("rigid_lid_windows = {}; expected >= 0 windows", options_.rigid_lid_windows));
  }
  if (options_.rigid_lid_windows > 0.0 && free_surface_ < 0) {
    throw ConfigError(fmt::format("rigid_lid_windows = {}; needs free_surface (a double body has no lid to release)",
                                  options_.rigid_lid_windows));
  }
}

const LinearizedFreeSurface* ResistanceMonitor::FreeSurface(const PimpleSolver& solver) const {
  return free_surface_ < 0 ? nullptr : dynamic_cast<const LinearizedFreeSurface*>(&solver.p().bc(free_surface_));
}

void ResistanceMonitor::StartPhase(double time) {
  start_time_ = time;
  phase_steps_ = 0;
  convergence_.emplace(convergence_->window(), options_.tolerance, options_.window_steps);
}

void ResistanceMonitor::Start(PimpleSolver& solver, bool restarted, const std::map<std::string, double>& checkpoint) {
  StartPhase(solver.time());
  started_ = true;
  if (restarted) {
    if (const auto it = checkpoint.find("resistance_release_time"); it != checkpoint.end()) release_time_ = it->second;
  }
  if (free_surface_ >= 0 && options_.rigid_lid_windows > 0.0) {
    auto& fs = dynamic_cast<LinearizedFreeSurface&>(solver.p().bc(free_surface_));
    if (!restarted) fs.SetRigidLid(true);
    if (fs.rigid_lid()) {
      lid_ = &fs;
      rigid_until_ = solver.time() + options_.rigid_lid_windows * convergence_->window();
    }
  }
  if (restarted || !options_.initial_velocity) return;
  VectorField& U = solver.U();
  for (int i = 0; i < solver.mesh().n_cells(); ++i) U[i] = options_.inflow;
}

std::map<std::string, double> ResistanceMonitor::CheckpointScalars() const {
  if (std::isnan(release_time_)) return {};
  return {{"resistance_release_time", release_time_}};
}

double ResistanceMonitor::TimeStep(double dt) const {
  if (options_.ramp_steps <= 1 || phase_steps_ >= options_.ramp_steps) return dt;
  return dt * (phase_steps_ + 1) / options_.ramp_steps;
}

bool ResistanceMonitor::Record(const PimpleSolver& solver, const Vector3& pressure, const Vector3& viscous) {
  const double rp = pressure.dot(direction_), rf = viscous.dot(direction_);
  const LinearizedFreeSurface* fs = FreeSurface(solver);
  std::span<const double> eta;
  double rwl = 0.0;
  if (fs) {
    eta = fs->eta();
    rwl = WaterlineForce(fs->surface(), eta, hull_, options_.rho, fs->options().g).dot(direction_);
  }
  const double forces[3] = {rp + rf, rp, rf};
  ++phase_steps_;
  if (lid_) {
    // Rigid-lid phase: no convergence test; release when its time is up.
    history_.push_back({solver.time(), rp + rf, rf, rp, rwl, std::nan(""), std::nan("")});
    if (solver.time() >= rigid_until_ * (1 - 1e-12)) {
      lid_->SetRigidLid(false);
      lid_ = nullptr;
      release_time_ = solver.time();
      StartPhase(solver.time());
    }
    return false;
  }
  convergence_->Add(solver.time(), forces, eta);
  const bool long_enough = solver.time() - start_time_ >= options_.min_windows * convergence_->window() * (1 - 1e-9);
  if (!converged_ && long_enough && convergence_->Converged()) {
    converged_ = true;
    converged_step_ = solver.step();
  }
  history_.push_back({solver.time(), rp + rf, rf, rp, rwl, convergence_->force_change(), convergence_->eta_change()});
  return converged_;
}

std::string ResistanceMonitor::Write(const std::filesystem::path& file, const PimpleSolver& solver) const {
  KELVIN_CHECK(!history_.empty(), "a recorded step before the report");
  const auto& last = history_.back();
  const double q = 0.5 * options_.rho * area_ * speed_ * speed_;
  const double rt = last[1], rf = last[2], rp = last[3], rwl = last[4];
  data::H5Writer w(file);
  auto scalar = [&](const std::string& name, double v, std::string_view units, std::string_view what) {
    w.WriteArray(name, std::span<const double>(&v, 1), {1}, units, what);
  };
  scalar("speed", speed_, "m/s", "inflow speed U");
  scalar("rho", options_.rho, "kg/m^3", "density");
  scalar("wetted_area", area_, "m^2", "wetted area at rest S (hull patch below z = 0)");
  scalar("R_T", rt, "N", "total resistance R_F + R_P along the inflow direction");
  scalar("R_F", rf, "N", "friction (wall shear) resistance");
  scalar("R_P", rp, "N", "pressure resistance");
  scalar("C_T", rt / q, "1", "R_T / (0.5 rho S U^2)");
  scalar("C_F", rf / q, "1", "R_F / (0.5 rho S U^2)");
  scalar("C_P", rp / q, "1", "R_P / (0.5 rho S U^2)");
  scalar("converged", converged_ ? 1.0 : 0.0, "1", "1 if the steady criterion stopped the run");
  scalar("converged_step", converged_step_, "1", "step at which the criterion was met (-1: not met)");
  scalar("tolerance", convergence_->tolerance(), "1", "relative change allowed over one window");
  scalar("window", convergence_->window(), "s", "pseudo-time window of the criterion (one flow-through)");
  scalar("flow_through", flow_through_, "s", "mesh extent along the inflow / U");
  scalar("release_time", release_time_, "s", "pseudo-time at which the rigid lid was released (NaN: never held)");
  std::string summary = fmt::format(
      "resistance on '{}': R_T = {:.5g} N (R_F {:.5g}, R_P {:.5g}); C_T = {:.5e}, C_F = {:.5e}, C_P = {:.5e} "
      "(S = {:.5g} m^2, U = {:.5g} m/s); {} (force change {:.2e}, eta change {:.2e} over {:.4g} s)",
      options_.hull_patch, rt, rf, rp, rt / q, rf / q, rp / q, area_, speed_,
      converged_ ? fmt::format("converged at step {}", converged_step_) : std::string("NOT converged"),
      convergence_->force_change(), convergence_->eta_change(), convergence_->window());
  if (options_.length > 0.0) {
    const double fn = speed_ / std::sqrt(options_.g * options_.length);
    scalar("Fn", fn, "1", "Froude number U / sqrt(g L)");
    summary += fmt::format("; Fn = {:.4f}", fn);
    if (options_.nu > 0.0) {
      scalar("Re", speed_ * options_.length / options_.nu, "1", "Reynolds number U L / nu");
      summary += fmt::format(", Re = {:.4g}", speed_ * options_.length / options_.nu);
    }
  }
  if (!options_.double_body.empty() && !std::filesystem::exists(options_.double_body)) {
    summary += fmt::format("; no wave-making part: the double-body result {} does not exist (run it first)",
                           options_.double_body.string());
  } else if (!options_.double_body.empty()) {
    // The wave-making part by coefficients, C_W = C_P - C_P(double body), so
    // a double-body run at another speed of the same grid serves (C_P of the
    // double body changes only through the Reynolds number).
    const data::H5Reader db(options_.double_body);
    const double cp_db = db.Read("C_P").at(0);
    const double s_db = db.Read("wetted_area").at(0), u_db = db.Read("speed").at(0);
    if (std::abs(s_db - area_) > 1e-6 * area_) {
      throw DataFileError(fmt::format("double_body {}: wetted area {} m^2; expected the same grid as this run ({} m^2)",
                                      options_.double_body.string(), s_db, area_));
    }
    scalar("C_P_double_body", cp_db, "1", "pressure resistance coefficient of the double-body run on the same grid");
    scalar("double_body_speed", u_db, "m/s", "speed of that double-body run");
    scalar("C_W", rp / q - cp_db, "1", "wave-making part C_P - C_P(double body)");
    scalar("R_W", (rp / q - cp_db) * q, "N", "wave-making resistance C_W 0.5 rho S U^2");
    summary += fmt::format("; wave-making C_W = C_P - C_P(double body at {:.4g} m/s) = {:.5e} (R_W = {:.5g} N)", u_db,
                           rp / q - cp_db, (rp / q - cp_db) * q);
  }
  const std::size_t rows = history_.size();
  std::vector<double> h(rows * 7);
  for (std::size_t r = 0; r < rows; ++r) std::copy(history_[r].begin(), history_[r].end(), h.begin() + 7 * r);
  w.WriteArray("history", h, {rows, 7}, "s, N, N, N, N, 1, 1",
               "per step: time, R_T, R_F, R_P, R_WL, force change, eta change (NaN before a full window)");
  {
    // Per hull face at the last step: where on the hull the resistance acts.
    const Mesh& mesh = solver.mesh();
    const Patch& patch = mesh.patches()[hull_];
    const PatchFaceForces ff = ComputePatchFaceForces(solver, hull_, options_.rho, options_.nu);
    const std::size_t n = static_cast<std::size_t>(patch.size);
    std::vector<double> centre(3 * n), area(3 * n), fp(3 * n), fv(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      const int f = patch.start + static_cast<int>(i);
      for (int d = 0; d < 3; ++d) {
        centre[3 * i + d] = mesh.face_centres()[f][d];
        area[3 * i + d] = mesh.face_areas()[f][d];
        fp[3 * i + d] = ff.pressure[i][d];
        fv[3 * i + d] = ff.viscous[i][d];
      }
    }
    w.WriteArray("hull_faces/centre", centre, {n, 3}, "m", "hull face centres (mesh axes)");
    w.WriteArray("hull_faces/area", area, {n, 3}, "m^2", "hull face area vectors, out of the water into the hull");
    w.WriteArray("hull_faces/pressure_force", fp, {n, 3}, "N", "pressure force of the water on each hull face");
    w.WriteArray("hull_faces/viscous_force", fv, {n, 3}, "N", "viscous force of the water on each hull face");
    w.WriteArray("hull_faces/direction", std::vector<double>{direction_.x(), direction_.y(), direction_.z()}, {3},
                 "1", "unit resistance direction d (R = F . d)");
  }
  if (const LinearizedFreeSurface* fs = FreeSurface(solver)) {
    scalar("R_WL", rwl, "N", "waterline-integral correction 0.5 rho g sum eta^2 n_x dl (not in R_T)");
    scalar("C_WL", rwl / q, "1", "R_WL / (0.5 rho S U^2)");
    summary += fmt::format("; waterline correction (separate) R_WL = {:.4g} N, C_WL = {:.3e}", rwl, rwl / q);
    const PatchSurface& s = fs->surface();
    const std::vector<double>& eta = fs->eta();
    const WaveProfile prof = HullWaveProfile(s, eta, hull_);
    const std::size_t m = prof.x.size();
    w.WriteArray("wave_profile/x", prof.x, {m}, "m", "waterline edge centre x (port y >= 0 first, then starboard)");
    w.WriteArray("wave_profile/y", prof.y, {m}, "m", "waterline edge centre y");
    w.WriteArray("wave_profile/eta", prof.eta, {m}, "m", "wave elevation at the hull");
    const int np = options_.wave_cut_points;
    std::vector<double> x(np);
    for (int k = 0; k < np; ++k) x[k] = s.min().x() + (s.max().x() - s.min().x()) * (k + 0.5) / np;
    for (std::size_t c = 0; c < options_.wave_cut_y.size(); ++c) {
      const double y0 = options_.wave_cut_y[c];
      const std::string grp = fmt::format("wave_cuts/cut{}", c);
      w.WriteArray(grp + "/x", x, {x.size()}, "m", "stations along the cut");
      w.WriteArray(grp + "/eta", WaveCut(s, eta, y0, x), {x.size()}, "m", "wave elevation (NaN outside the patch)");
      w.SetAttribute(grp, "y", y0);
    }
    // The whole pattern, face by face, for plots and comparisons (h5py).
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
    w.WriteArray("surface/damping", fs->damping(), {nf}, "1/s", "beach damping rate (0 outside the beaches)");
    const double mx = *std::max_element(eta.begin(), eta.end()), mn = *std::min_element(eta.begin(), eta.end());
    scalar("eta_max", mx, "m", "largest wave elevation on the patch");
    scalar("eta_min", mn, "m", "lowest wave elevation on the patch");
  }
  w.Commit();
  return summary;
}

std::unique_ptr<ResistanceMonitor> LoadResistance(const data::ConfigNode& node, const PimpleSolver& solver,
                                                  const data::ConfigNode& physics,
                                                  const std::filesystem::path& case_dir) {
  node.ExpectKeys({"hull", "free_surface", "inflow", "wetted_area", "length", "wave_cuts", "wave_cut_points",
                   "double_body", "steady"});
  ResistanceOptions o;
  o.hull_patch = node.Get<std::string>("hull", o.hull_patch);
  o.free_surface_patch = node.Get<std::string>("free_surface", "");
  const std::vector<double> u = node["inflow"].As<std::vector<double>>();
  if (u.size() != 3) node["inflow"].Fail("a list of 3 numbers [u, v, w] (m/s)");
  o.inflow = Vector3(u[0], u[1], u[2]);
  o.rho = physics.Get<double>("rho", 1000.0);
  o.nu = physics.Get<double>("nu", 0.0);
  if (node.Has("wetted_area")) o.wetted_area = node.GetPositive("wetted_area");
  if (node.Has("length")) o.length = node.GetPositive("length");
  if (node.Has("wave_cuts")) {
    for (const data::ConfigNode& item : node["wave_cuts"].Items()) o.wave_cut_y.push_back(item.As<double>());
  }
  o.wave_cut_points = node.Get<int>("wave_cut_points", o.wave_cut_points);
  if (node.Has("double_body")) {
    o.double_body = node.Get<std::string>("double_body");
    if (o.double_body.is_relative()) o.double_body = case_dir / o.double_body;
  }
  if (node.Has("steady")) {
    const data::ConfigNode st = node["steady"];
    st.ExpectKeys({"tolerance", "window", "window_steps", "min_windows", "initial_velocity", "ramp_steps",
                   "rigid_lid_windows"});
    o.window_steps = st.Get<int>("window_steps", o.window_steps);
    if (st.Has("tolerance")) o.tolerance = st.GetPositive("tolerance");
    if (st.Has("window")) o.window = st.Get<double>("window");
    if (st.Has("min_windows")) o.min_windows = st.GetPositive("min_windows");
    o.initial_velocity = st.Get<bool>("initial_velocity", o.initial_velocity);
    o.ramp_steps = st.Get<int>("ramp_steps", o.ramp_steps);
    o.rigid_lid_windows = st.Get<double>("rigid_lid_windows", o.rigid_lid_windows);
  }
  if (!o.free_surface_patch.empty()) {
    const int k = solver.mesh().FindPatch(o.free_surface_patch);
    if (k >= 0) {
      if (const auto* fs = dynamic_cast<const LinearizedFreeSurface*>(&solver.p().bc(k))) o.g = fs->options().g;
    }
  }
  try {
    return std::make_unique<ResistanceMonitor>(solver, std::move(o));
  } catch (const ConfigError& e) {
    node.Fail(e.what());
  }
}

}  // namespace kelvin::cfd
