#include "cfd/motion/ship_forces.h"

#include "data/schema/errors.h"

namespace kelvin::cfd {

PatchFaceForces ComputePatchFaceForces(const PimpleSolver& s, int patch_index, double rho, double nu) {
  const Mesh& mesh = s.mesh();
  const Patch& patch = mesh.patches()[patch_index];
  const int ni = mesh.n_internal_faces();
  const auto& bc = s.U().bc(patch_index);
  PatchFaceForces out;
  out.pressure.resize(patch.size);
  out.viscous.resize(patch.size);
  for (int i = 0; i < patch.size; ++i) {
    const int f = patch.start + i;
    // S_f points out of the water, into the body: the pressure pushes along
    // it; the wall shear stress on the body is -mu dU/dn_out.
    out.pressure[i] = rho * s.p().boundary()[f - ni] * mesh.face_areas()[f];
    const Vector3 sn_grad = bc.gradient_internal()[i].cwiseProduct(s.U()[mesh.owner()[f]]) + bc.gradient_boundary()[i];
    // With a turbulence model the face carries nu + nu_t,wall (wall functions).
    const double nu_f = s.turbulence() ? s.FaceViscosity(f) : nu;
    out.viscous[i] = -rho * nu_f * sn_grad * mesh.face_area_magnitudes()[f];
  }
  return out;
}

HullLoads SumHullLoads(const Mesh& mesh, std::span<const int> patches,
                       std::span<const PatchFaceForces* const> faces, const Pose& pose,
                       const Vector3& centre_body) {
  KELVIN_CHECK(faces.size() == patches.size(), "the face forces of every patch");
  const Eigen::Matrix3d R = pose.Rotation();
  const Vector3 centre = R * centre_body + pose.Translation(centre_body);
  Vector3 fp = Vector3::Zero(), fv = Vector3::Zero(), mp = Vector3::Zero(), mv = Vector3::Zero();
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const Patch& patch = mesh.patches()[patches[k]];
    const PatchFaceForces& ff = *faces[k];
    for (int i = 0; i < patch.size; ++i) {
      const Vector3 arm = mesh.face_centres()[patch.start + i] - centre;
      fp += ff.pressure[i];
      fv += ff.viscous[i];
      mp += arm.cross(ff.pressure[i]);
      mv += arm.cross(ff.viscous[i]);
    }
  }
  // Earth (z up) -> grid axes (x forward, y port, z up) -> ship axes
  // (x forward, y starboard, z down).
  auto to_ship = [&](const Vector3& f_earth, const Vector3& m_earth) {
    const Vector3 f = R.transpose() * f_earth;
    const Vector3 m = R.transpose() * m_earth;
    return PlanarLoad{f.x(), -f.y(), -m.z()};
  };
  return {to_ship(fp, mp), to_ship(fv, mv)};
}

HullLoads ComputeHullLoads(const PimpleSolver& s, std::span<const int> patches, double rho,
                           double nu, const Pose& pose, const Vector3& centre_body) {
  std::vector<PatchFaceForces> faces;
  for (int k : patches) faces.push_back(ComputePatchFaceForces(s, k, rho, nu));
  std::vector<const PatchFaceForces*> views;
  for (const PatchFaceForces& f : faces) views.push_back(&f);
  HullLoads loads = SumHullLoads(s.mesh(), patches, views, pose, centre_body);
  SumOverRanks(s.part(), loads);
  return loads;
}

void SumOverRanks(const DomainPart* part, HullLoads& l) {
  if (!part || !part->parallel()) return;
  double v[6] = {l.pressure.X, l.pressure.Y, l.pressure.N, l.viscous.X, l.viscous.Y, l.viscous.N};
  part->SumInPlace(v);
  l.pressure = {v[0], v[1], v[2]};
  l.viscous = {v[3], v[4], v[5]};
}

PlanarLoad PrimeScales::ToPrime(const PlanarLoad& load) const {
  const double force = 0.5 * rho * length * draft * speed * speed;
  return {load.X / force, load.Y / force, load.N / (force * length)};
}

void WriteCaptiveHistory(data::H5Writer& w, const std::vector<CaptiveSample>& rows) {
  const std::size_t n = rows.size();
  auto series = [&](const std::string& name, auto get, std::string_view units,
                    std::string_view description) {
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = get(rows[i]);
    w.WriteArray("captive/" + name, v, {n}, units, description);
  };
  series(
      "time", [](const CaptiveSample& r) { return r.time; }, "s", "time");
  series(
      "X", [](const CaptiveSample& r) { return r.loads.Total().X; }, "N", "surge force, ship axes");
  series(
      "Y", [](const CaptiveSample& r) { return r.loads.Total().Y; }, "N",
      "sway force, ship axes (starboard)");
  series(
      "N", [](const CaptiveSample& r) { return r.loads.Total().N; }, "N m",
      "yaw moment about the reference point");
  series(
      "X_pressure", [](const CaptiveSample& r) { return r.loads.pressure.X; }, "N",
      "pressure part of X");
  series(
      "Y_pressure", [](const CaptiveSample& r) { return r.loads.pressure.Y; }, "N",
      "pressure part of Y");
  series(
      "N_pressure", [](const CaptiveSample& r) { return r.loads.pressure.N; }, "N m",
      "pressure part of N");
  series(
      "X_viscous", [](const CaptiveSample& r) { return r.loads.viscous.X; }, "N",
      "viscous part of X");
  series(
      "Y_viscous", [](const CaptiveSample& r) { return r.loads.viscous.Y; }, "N",
      "viscous part of Y");
  series(
      "N_viscous", [](const CaptiveSample& r) { return r.loads.viscous.N; }, "N m",
      "viscous part of N");
  series(
      "X_prime", [](const CaptiveSample& r) { return r.prime.X; }, "1", "X / (0.5 rho L T U^2)");
  series(
      "Y_prime", [](const CaptiveSample& r) { return r.prime.Y; }, "1", "Y / (0.5 rho L T U^2)");
  series(
      "N_prime", [](const CaptiveSample& r) { return r.prime.N; }, "1", "N / (0.5 rho L^2 T U^2)");
  series(
      "x0", [](const CaptiveSample& r) { return r.pose.x0; }, "m",
      "earth position of the reference point");
  series(
      "y0", [](const CaptiveSample& r) { return r.pose.y0; }, "m",
      "earth position, starboard positive");
  series(
      "psi", [](const CaptiveSample& r) { return r.pose.psi; }, "rad",
      "heading, starboard positive");
  series(
      "u", [](const CaptiveSample& r) { return r.pose.u(); }, "m/s", "surge velocity, ship axes");
  series(
      "v", [](const CaptiveSample& r) { return r.pose.v(); }, "m/s", "sway velocity, ship axes");
  series(
      "r", [](const CaptiveSample& r) { return r.pose.r; }, "rad/s", "yaw rate");
}

}  // namespace kelvin::cfd
