// A bridge on memq:// (or another LCM URL) running on its own thread with
// its browser display on a free loopback port, for the display and flood
// tests. Its listener shares the bridge's LCM instance.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bridge/bridge.h"
#include "bridge/display_feed.h"
#include "bridge/http_display.h"
#include "bridge/listener.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/test_utilities/test_utilities.h"
// Last: httplib.h brings <resolv.h>, whose _res macro breaks Eigen's headers.
#include <httplib.h>

namespace kelvin::testing {

// The LCM states are read once the bridge has stopped.
class RunningBridge {
 public:
  explicit RunningBridge(bridge::BridgeOptions o, bridge::HttpDisplayOptions h = {},
                         const std::string& lcm_url = "memq://")
      : lcm_(lcm_url) {
    ship_ = sim::LoadShip(SourceDir() / "data/ships/kvlcc2.yaml");
    bridge_ = std::make_unique<bridge::Bridge>(ship_, o, lcm_);
    listener_ = std::make_unique<bridge::Listener>(lcm_, "KELVIN");
    bridge::DisplayInfo info;
    info.ship = ship_.name;
    info.script = o.script;
    info.derivatives = "a published reference set, not checked against this project's CFD";
    info.helm_source = bridge::kPageHelmSource;
    info.origin_latitude = o.origin.latitude;
    info.origin_longitude = o.origin.longitude;
    h.port = 0;
    display_ = std::make_unique<bridge::HttpDisplay>(feed_, info, h);
    bridge_->SetDisplay(&feed_);
    thread_ = std::thread([this] { summary_ = bridge_->Run(); });
  }
  ~RunningBridge() { Stop(); }
  void Stop() {
    bridge_->RequestStop();
    if (thread_.joinable()) thread_.join();
  }
  // Waits for the run to end by itself.
  void Join() {
    if (thread_.joinable()) thread_.join();
  }
  const std::vector<kelvin::ship_state_t>& States() {
    while (lcm_.handleTimeout(0) > 0) {
    }
    return listener_->states();
  }
  httplib::Client Client() const { return httplib::Client("127.0.0.1", display_->port()); }
  const bridge::HttpDisplay& display() const { return *display_; }
  const bridge::DisplayFeed& feed() const { return feed_; }
  std::string Url(const std::string& query = "") const { return display_->url() + query; }
  const bridge::BridgeSummary& summary() const { return summary_; }
  const bridge::Bridge& bridge() const { return *bridge_; }

 private:
  lcm::LCM lcm_;
  sim::ShipParameters ship_;
  std::unique_ptr<bridge::Bridge> bridge_;
  std::unique_ptr<bridge::Listener> listener_;
  bridge::DisplayFeed feed_;
  std::unique_ptr<bridge::HttpDisplay> display_;
  bridge::BridgeSummary summary_;
  std::thread thread_;
};

}  // namespace kelvin::testing
