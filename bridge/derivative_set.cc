#include "bridge/derivative_set.h"

#include <fmt/format.h>

#include "data/schema/config.h"
#include "data/schema/errors.h"

namespace kelvin::bridge {

DerivativeSet LoadDerivativeSet(const std::filesystem::path& path) {
  const data::ConfigNode root = data::ConfigNode::LoadFile(path);
  if (!root.IsMap()) root.Fail("a derivative set (a map with a 'hull' section)");
  // The sections `kelvin identify` writes (identification/derivative_set_io.h),
  // and the check.
  root.ExpectKeys({"derivative_set", "hull", "standard_errors", "fit", "check"});
  DerivativeSet set;
  set.file = path.string();
  if (const auto meta = root.Find("derivative_set")) {
    meta->ExpectKeys({"name", "ship", "source"});
    set.name = meta->Get<std::string>("name", "");
  }
  const data::ConfigNode hull = root["hull"];
  std::vector<std::string> names;
  for (const auto& n : sim::HullCoefficients<double>::kNames) names.emplace_back(n);
  hull.ExpectKeys(names);
  for (int i = 0; i < sim::HullCoefficients<double>::kCount; ++i) {
    set.hull[i] = hull.Get<double>(names[static_cast<std::size_t>(i)]);
    if (!std::isfinite(set.hull[i])) hull[names[static_cast<std::size_t>(i)]].Fail("a finite number");
  }
  if (const auto check = root.Find("check")) {
    check->ExpectKeys({"passed", "reference", "date", "summary"});
    DerivativeCheck c;
    c.passed = check->Get<bool>("passed");
    c.reference = check->Get<std::string>("reference", "");
    c.date = check->Get<std::string>("date", "");
    c.summary = check->Get<std::string>("summary", "");
    set.check = c;
  }
  return set;
}

DerivativeAssessment AssessDerivatives(const sim::ShipParameters& ship, const std::optional<DerivativeSet>& set,
                                       bool require_checked) {
  DerivativeAssessment a;
  if (!set) {
    a.status = DerivativeStatus::kShipReference;
    a.message = fmt::format(
        "streaming the hull derivatives of the ship file ('{}', {}): a published reference set, not checked "
        "against this project's CFD",
        ship.name, ship.source.empty() ? "no source given" : ship.source);
  } else if (!set->check) {
    a.status = DerivativeStatus::kUnchecked;
    a.message = fmt::format("derivative set {} has no 'check' section: it was never checked against CFD", set->file);
  } else if (!set->check->passed) {
    a.status = DerivativeStatus::kCheckFailed;
    a.message = fmt::format("derivative set {} FAILED its check against CFD ({}{})", set->file,
                            set->check->reference.empty() ? "no reference given" : set->check->reference,
                            set->check->summary.empty() ? "" : ": " + set->check->summary);
  } else {
    a.status = DerivativeStatus::kChecked;
    a.message = fmt::format("derivative set {} passed its check against {}", set->file,
                            set->check->reference.empty() ? "CFD" : set->check->reference);
    return a;
  }
  if (require_checked) {
    throw ArgumentError(fmt::format("--require-checked: refusing to stream: {}", a.message));
  }
  return a;
}

}  // namespace kelvin::bridge
