// The bridge's browser display: an HTTP server (cpp-httplib, from Debian's
// libcpp-httplib-dev) on its own threads, bound to loopback unless the user
// names another address. It serves the page compiled into kelvin
// (bridge/display/), the state as server-sent events at `update_rate`, the
// thinned track, and the page's helm: one page holds it at a time, and its
// orders go into the DisplayFeed's inbox, which the real-time loop drains
// into the same HelmFilter as the LCM helm commands.
//
//   GET  /              the page            GET  /display.js   its script
//   GET  /state         one update (JSON)   GET  /stream       updates (text/event-stream)
//   GET  /track         the thinned track   POST /helm/claim   -> {"token": ...} or 409
//   POST /helm          token, rudder (deg, + starboard), rps (1/s): form fields
//   POST /helm/release  token
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "bridge/display_feed.h"
#include "bridge/display_json.h"
#include "bridge/helm_holder.h"

namespace httplib {
class Server;
struct Request;
struct Response;
}  // namespace httplib

namespace kelvin::bridge {

// The source_id of the page's helm orders in the helm filter (list it with
// --helm-source where the sources are restricted).
constexpr int kPageHelmSource = 1000;

struct HttpDisplayOptions {
  std::string host = "127.0.0.1";  // loopback unless the user names another address
  int port = 8080;                 // 0: any free port (tests)
  double update_rate = 20;         // Hz of wall-clock time, event-stream updates, 10 to 50
  std::size_t max_body = 1024;     // bytes of a request body; larger ones get 413 and are counted
  int max_streams = 8;             // open event streams (pages watching)
  double helm_lapse = 10;          // s without an order before the holder loses the helm

  // Parses "--http" text: "host:port" with a numeric IPv4 host.
  static HttpDisplayOptions Parse(std::string_view text);
  void Validate() const;  // throws kelvin::ArgumentError naming the option
};

class HttpDisplay {
 public:
  // Binds and starts serving; throws kelvin::ArgumentError if the address
  // cannot be bound. `feed` must outlive the display.
  HttpDisplay(DisplayFeed& feed, DisplayInfo info, const HttpDisplayOptions& options);
  ~HttpDisplay();  // stops the server and joins its threads
  HttpDisplay(const HttpDisplay&) = delete;
  HttpDisplay& operator=(const HttpDisplay&) = delete;

  int port() const { return port_; }
  std::string url() const;
  PageCounters counters() const;

 private:
  void AddRoutes();
  void Stream(const httplib::Request& req, httplib::Response& res);
  void Helm(const httplib::Request& req, httplib::Response& res);
  void Claim(httplib::Response& res);
  void Release(const httplib::Request& req, httplib::Response& res);
  void Count(long PageCounters::*counter);
  std::string StateText();

  DisplayFeed& feed_;
  DisplayInfo info_;
  HttpDisplayOptions options_;
  HelmHolder holder_;
  mutable std::mutex counters_mutex_;
  PageCounters counters_;
  std::atomic<bool> stopping_{false};
  std::atomic<bool> listen_returned_{false};
  std::unique_ptr<httplib::Server> server_;
  int port_ = 0;
  std::thread thread_;
};

}  // namespace kelvin::bridge
