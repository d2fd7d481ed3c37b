// kelvin bridge: the simulator in real time over LCM, helm commands in,
// ship state, maneuver events and NMEA 0183 out.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <memory>
#include <string>
#include <vector>

#include "bridge/bridge.h"
#include "bridge/derivative_set.h"
#include "data/schema/errors.h"
#include "simulator/mmg/ship_parameters.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {

namespace {

struct BridgeArgs {
  std::string ship_file;
  std::string derivatives;
  bool require_checked = false;
  bridge::BridgeOptions options;
  std::string lcm_url;
  std::string nmea;
  std::string origin;
  std::vector<int> helm_sources;
};

std::atomic<bridge::Bridge*> g_running_bridge{nullptr};

extern "C" void StopBridge(int /*signal*/) {
  if (bridge::Bridge* b = g_running_bridge.load()) b->RequestStop();
}

bridge::GeoPoint ParseOrigin(const std::string& text) {
  const std::size_t comma = text.find(',');
  bridge::GeoPoint p;
  try {
    if (comma == std::string::npos) throw std::invalid_argument("no comma");
    std::size_t used_lat = 0, used_lon = 0;
    const std::string lat = text.substr(0, comma), lon = text.substr(comma + 1);
    p.latitude = std::stod(lat, &used_lat);
    p.longitude = std::stod(lon, &used_lon);
    if (used_lat != lat.size() || used_lon != lon.size()) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw ArgumentError(fmt::format("--origin '{}': expected <latitude>,<longitude> in degrees, e.g. 53.5,3.0", text));
  }
  return p;
}

const char* StatusName(bridge::BridgeStatus s) {
  switch (s) {
    case bridge::BridgeStatus::kCompleted: return "completed";
    case bridge::BridgeStatus::kStopped: return "stopped";
    case bridge::BridgeStatus::kDiverged: return "DIVERGED (non-finite state)";
  }
  return "?";
}

void RunBridge(BridgeArgs& a) {
  sim::ShipParameters ship = sim::LoadShip(a.ship_file);
  std::optional<sim::DerivativeSet> set;
  if (!a.derivatives.empty()) {
    set = sim::LoadDerivativeSet(a.derivatives);
    ship.hull = set->hull;
    ship.has_hull = true;
    ship.Validate(a.derivatives);
  }
  sim::RequireManeuveringModel(ship, a.ship_file);
  const bridge::DerivativeAssessment assessment = bridge::AssessDerivatives(ship, set, a.require_checked);
  if (assessment.status == bridge::DerivativeStatus::kChecked) {
    spdlog::info("{}", assessment.message);
  } else {
    spdlog::warn("*** UNCHECKED HULL DERIVATIVES *** {}", assessment.message);
    spdlog::warn("*** the streamed motion is not validated against CFD; --require-checked refuses such a set ***");
  }

  bridge::BridgeOptions& o = a.options;
  if (!a.nmea.empty()) o.nmea = bridge::UdpEndpoint::Parse(a.nmea, "--nmea");
  if (!a.origin.empty()) o.origin = ParseOrigin(a.origin);
  o.helm.sources.assign(a.helm_sources.begin(), a.helm_sources.end());
  o.Validate();

  lcm::LCM lcm(a.lcm_url);
  if (!lcm.good()) {
    throw ArgumentError(fmt::format("--lcm-url '{}': LCM cannot open this URL (expected e.g. udpm://239.255.76.67:7667?ttl=0 "
                                    "or memq://)",
                                    a.lcm_url));
  }
  bridge::Bridge bridge(ship, o, lcm);
  spdlog::info("bridge: {} at {} Hz (step {} s x {}), speedup {}, {}; channels {}, {}, {}{}", ship.name, o.rate,
               bridge.step(), bridge.steps_per_state(), o.speedup,
               o.script.empty() ? std::string("helm commands steer") : "script " + o.script, bridge.state_channel(),
               bridge.helm_channel(), bridge.event_channel(),
               o.nmea ? fmt::format(", NMEA 0183 to {} at {} Hz", o.nmea->ToString(), o.nmea_rate) : std::string());

  g_running_bridge.store(&bridge);
  struct sigaction sa {};
  sa.sa_handler = StopBridge;
  sigemptyset(&sa.sa_mask);
  struct sigaction old_int {}, old_term {};
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
  const bridge::BridgeSummary s = bridge.Run();
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  g_running_bridge.store(nullptr);

  const auto& h = s.helm;
  fmt::print("bridge {}: t = {:.3f} s, {} states, {} events published ({} failed)\n", StatusName(s.status), s.sim_time,
             s.states_published, s.events_published, s.publish_failures);
  fmt::print("  helm: {} received, {} accepted ({} clamped), {} rejected: {} malformed, {} not finite, {} out of range, "
             "{} stale, {} from the future, {} unknown source; {} ignored while scripted\n",
             h.received, h.accepted, h.clamped, h.rejected(), h.malformed, h.not_finite, h.out_of_range, h.stale,
             h.future, h.unknown_source, s.helm_ignored_scripted);
  fmt::print("  pacing{}: {} late ticks, {} resyncs, max lateness {:.3f} ms\n", s.realtime ? " (SCHED_FIFO)" : "",
             s.late_ticks, s.resyncs, s.max_lateness * 1e3);
  if (o.nmea) fmt::print("  nmea: {} sentences sent, {} dropped\n", s.nmea_sentences_sent, s.nmea_sentences_dropped);
  if (s.status == bridge::BridgeStatus::kDiverged) {
    throw std::runtime_error(fmt::format("simulation diverged at t = {} s", s.sim_time));
  }
}

}  // namespace

Command AddBridgeCommand(CLI::App& app) {
  auto args = std::make_shared<BridgeArgs>();
  CLI::App* cmd = app.add_subcommand("bridge", "Stream the simulator in real time over LCM (helm in, state/NMEA out)");
  cmd->add_option("ship", args->ship_file, "Ship file (data/ships/<ship>.yaml)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--derivatives", args->derivatives, "Derivative set replacing the ship file's hull section")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--require-checked", args->require_checked,
                "Refuse to stream hull derivatives without a passing check against CFD");
  auto& o = args->options;
  cmd->add_option("--rate", o.rate, "State messages per second of simulation time (Hz)")->capture_default_str();
  cmd->add_option("--speedup", o.speedup, "Simulation seconds per wall-clock second")->capture_default_str();
  cmd->add_option("--script", o.script,
                  "Play an IMO maneuver: turning:<deg>:stbd|port, zigzag:<deg>/<deg>:stbd|port, spiral:<max>:<step>");
  cmd->add_option("--duration", o.duration, "Simulation time in s (0: until the script ends, or until Ctrl-C)")
      ->capture_default_str();
  cmd->add_option("--step", o.step, "Integrator step in s dividing 1/rate (default: at most Lpp/U0/200)");
  cmd->add_option("--speed", o.approach_speed, "Initial speed in m/s (default: the ship file's approach speed)");
  cmd->add_option("--lcm-url", args->lcm_url, "LCM URL (default: LCM's, e.g. udpm://239.255.76.67:7667?ttl=0)");
  cmd->add_option("--channel-prefix", o.channel_prefix, "Channels <prefix>_STATE, <prefix>_HELM, <prefix>_EVENT")
      ->capture_default_str();
  cmd->add_option("--nmea", args->nmea, "Send NMEA 0183 over UDP to host:port (without a value: 127.0.0.1:10110)")
      ->expected(0, 1)
      ->default_str("127.0.0.1:10110");
  cmd->add_option("--nmea-rate", o.nmea_rate, "NMEA fixes per wall-clock second, 1 to 10")->capture_default_str();
  cmd->add_option("--origin", args->origin, "Latitude,longitude in deg of the start position (default 53.5,3.0)");
  cmd->add_option("--stale-timeout", o.helm.stale_timeout, "Reject helm commands older than this (s)")
      ->capture_default_str();
  cmd->add_option("--realtime-priority", o.realtime_priority,
                  "Run the loop with SCHED_FIFO at this priority, 1-99 (needs root or CAP_SYS_NICE)");
  cmd->add_option("--helm-source", args->helm_sources, "Accept helm commands only from this source_id (repeatable)");
  return {cmd, [args] { RunBridge(*args); }};
}

}  // namespace kelvin::cli
