// Captive seeds: a small KVLCC2 campaign (a static drift and a pure sway
// run) written by the project's own writers as HDF5 and as one CSV per run.
#include <cmath>

#include "data/schema/campaign_file.h"
#include "data/schema/captive_io.h"
#include "tests/fuzz/seeds/seeds.h"

namespace kelvin::fuzz {
namespace {

namespace fs = std::filesystem;

data::CaptiveRun Run(const char* name, data::MotionKind kind, int samples) {
  data::CaptiveRun r;
  r.name = name;
  r.motion.kind = kind;
  r.motion.U = 1.0;
  r.motion.beta = kind == data::MotionKind::kStaticDrift ? 0.1 : 0.0;
  r.motion.y_a = kind == data::MotionKind::kPureSway ? 0.05 : 0.0;
  r.motion.omega = kind == data::MotionKind::kPureSway ? 2.0 : 0.0;
  r.motion.t_ramp = 1.0;
  for (int i = 0; i < samples; ++i) {
    const double t = 0.1 * i;
    r.time.push_back(t);
    for (int c = 0; c < 3; ++c) r.force[c].push_back((c + 1) * std::sin(r.motion.omega * t + c));
  }
  return r;
}


}  // namespace

void WriteCaptiveSeeds(const fs::path& source_dir, const fs::path& out) {
  data::CaptiveCampaign c;
  c.description = "fuzz seed";
  c.ship = data::LoadCaptiveShip(source_dir / "data/ships/kvlcc2.yaml");
  c.runs = {Run("drift", data::MotionKind::kStaticDrift, 40), Run("sway", data::MotionKind::kPureSway, 80)};
  fs::create_directories(out / "captive_h5");
  data::WriteCampaignH5(c, out / "captive_h5" / "kvlcc2.h5");
  for (const auto& run : c.runs) data::WriteRunCsv(run, out / "captive_csv" / (run.name + ".csv"));
  WriteSeed(out / "captive_csv", "units.csv", "# kind: static_drift\n# U: 1\ntime [s],X [N],Y [N],N [Nm]\n0,1,2,3\n");
}

}  // namespace kelvin::fuzz
