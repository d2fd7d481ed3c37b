// Exact conservation after the pressure correction and bitwise restart from
// an HDF5 checkpoint.
#include <gtest/gtest.h>

#include <cstring>

#include "cfd/io/checkpoint.h"
#include "cfd/mesh/box_mesh.h"
#include "tests/cfd/cfd_test_support.h"

namespace kelvin::cfd {
namespace {

// Channel with inflow, fixed-pressure outflow, a lid moving along x and an
// obstacle-free box; perturbed or polyhedral cells.
std::unique_ptr<PimpleSolver> MakeChannel(const Mesh& mesh, TimeScheme time, int n_outer, double final_tolerance) {
  auto U = testing::MakeField<Vector3>("U", mesh, [](const Patch& p) -> std::unique_ptr<BoundaryCondition<Vector3>> {
    if (p.name == "xmin") return std::make_unique<FixedValue<Vector3>>(ValueFunction<Vector3>(
        [](const Vector3& x, double) { return Vector3(4.0 * x.y() * (1.0 - x.y()), 0.0, 0.0); }));
    if (p.name == "xmax") return std::make_unique<InletOutlet<Vector3>>(Vector3(0, 0, 0));
    if (p.name == "ymax") return std::make_unique<MovingWall>([](double t) {
      MovingWall::Motion m;
      m.velocity = Vector3(0.5 * std::sin(3.0 * t), 0.0, 0.0);
      return m;
    });
    if (p.kind == PatchKind::kSymmetry) return std::make_unique<Slip>();
    return std::make_unique<FixedValue<Vector3>>(Vector3(0, 0, 0));
  });
  auto p = testing::MakeField<double>("p", mesh, [](const Patch& patch) -> std::unique_ptr<BoundaryCondition<double>> {
    if (patch.name == "xmax") return std::make_unique<FixedValue<double>>(0.0);
    return std::make_unique<ZeroGradient<double>>();
  });
  PhysicsOptions physics;
  physics.nu = 0.01;
  SchemeOptions schemes;
  schemes.time = time;
  schemes.gradient.scheme = GradientScheme::kLeastSquares;
  schemes.skew_correction = true;
  PimpleOptions pimple;
  pimple.n_outer = n_outer;
  pimple.relax_U = 0.8;
  pimple.relax_p = 0.5;
  pimple.n_correctors = 2;
  pimple.n_non_orthogonal = 2;
  pimple.pressure_final_relative_tolerance = final_tolerance;
  return std::make_unique<PimpleSolver>(mesh, physics, schemes, pimple, std::move(U), std::move(p));
}

Mesh ChannelMesh(bool polyhedral) {
  BoxMeshOptions mo;
  mo.cells = {12, 8, 4};
  mo.max = Vector3(2.0, 1.0, 0.5);
  mo.perturbation = polyhedral ? 0.0 : 0.2;
  mo.polyhedral = polyhedral;
  mo.kinds[4] = mo.kinds[5] = PatchKind::kSymmetry;
  mo.kinds[0] = mo.kinds[1] = PatchKind::kPatch;
  Mesh mesh = MakeBoxMesh(mo);
  mesh.RenumberCells();
  return mesh;
}

TEST(Conservation, FluxesSumToZeroPerCellAndGlobally) {
  for (bool polyhedral : {false, true}) {
    const Mesh mesh = ChannelMesh(polyhedral);
    auto solver = MakeChannel(mesh, TimeScheme::kBackward, 2, 1e-14);
    double worst = 0.0, worst_global = 0.0;
    for (int i = 0; i < 10; ++i) {
      const StepSummary s = solver->Step(0.02);
      ASSERT_TRUE(s.finite);
      worst = std::max(worst, s.continuity_error);
      worst_global = std::max(worst_global, s.global_mass_imbalance);
      // Independent check from the flux field itself.
      std::vector<double> sum(mesh.n_cells(), 0.0), mag(mesh.n_cells(), 0.0);
      for (int f = 0; f < mesh.n_faces(); ++f) {
        sum[mesh.owner()[f]] += solver->flux()[f];
        mag[mesh.owner()[f]] += std::abs(solver->flux()[f]);
        if (f < mesh.n_internal_faces()) {
          sum[mesh.neighbour()[f]] -= solver->flux()[f];
          mag[mesh.neighbour()[f]] += std::abs(solver->flux()[f]);
        }
      }
      for (int c = 0; c < mesh.n_cells(); ++c) EXPECT_LE(std::abs(sum[c]), 1e-10 * mag[c]) << "cell " << c;
    }
    std::printf("%s: max per-cell continuity error %.3e, global imbalance %.3e\n",
                polyhedral ? "polyhedral" : "perturbed hex", worst, worst_global);
    EXPECT_LE(worst, 1e-10);
    EXPECT_LE(worst_global, 1e-12);
  }
}

bool BitwiseEqual(const void* a, const void* b, std::size_t bytes) { return std::memcmp(a, b, bytes) == 0; }

TEST(Restart, CheckpointContinuesBitForBit) {
  kelvin::testing::ScopedTempDir tmp;
  const Mesh mesh = ChannelMesh(false);
  constexpr int kSteps = 8;
  auto straight = MakeChannel(mesh, TimeScheme::kBackward, 2, 1e-8);
  for (int i = 0; i < kSteps; ++i) ASSERT_TRUE(straight->Step(0.02).finite);

  auto first = MakeChannel(mesh, TimeScheme::kBackward, 2, 1e-8);
  for (int i = 0; i < kSteps / 2; ++i) ASSERT_TRUE(first->Step(0.02).finite);
  WriteCheckpoint(tmp / "checkpoint.h5", *first);
  first.reset();
  auto resumed = MakeChannel(mesh, TimeScheme::kBackward, 2, 1e-8);
  ReadCheckpoint(tmp / "checkpoint.h5", *resumed);
  for (int i = 0; i < kSteps / 2; ++i) ASSERT_TRUE(resumed->Step(0.02).finite);

  EXPECT_EQ(straight->step(), resumed->step());
  EXPECT_EQ(straight->time(), resumed->time());
  ASSERT_EQ(straight->U().values().size(), resumed->U().values().size());
  EXPECT_TRUE(BitwiseEqual(straight->U().values().data(), resumed->U().values().data(),
                           sizeof(Vector3) * straight->U().values().size()));
  EXPECT_TRUE(BitwiseEqual(straight->p().values().data(), resumed->p().values().data(),
                           sizeof(double) * straight->p().values().size()));
  EXPECT_TRUE(BitwiseEqual(straight->flux().data(), resumed->flux().data(), sizeof(double) * straight->flux().size()));
  // The flow did change over the run (the test is not trivially true).
  double max_u = 0.0;
  for (const Vector3& u : straight->U().values()) max_u = std::max(max_u, u.norm());
  EXPECT_GT(max_u, 0.5);
}

TEST(Restart, CheckpointOfAnotherMeshIsAClearError) {
  kelvin::testing::ScopedTempDir tmp;
  const Mesh mesh = ChannelMesh(false);
  auto a = MakeChannel(mesh, TimeScheme::kEuler, 1, 1e-8);
  a->Step(0.02);
  WriteCheckpoint(tmp / "c.h5", *a);
  const Mesh other = ChannelMesh(true);
  auto b = MakeChannel(other, TimeScheme::kEuler, 1, 1e-8);
  EXPECT_THROW(ReadCheckpoint(tmp / "c.h5", *b), DataFileError);
}

}  // namespace
}  // namespace kelvin::cfd
