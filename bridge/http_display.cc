#include "bridge/http_display.h"

#include <fmt/format.h>
#include <httplib.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>

#include "bridge/display_page.h"
#include "bridge/nmea.h"
#include "bridge/pacer.h"
#include "data/schema/errors.h"

namespace kelvin::bridge {

namespace {

constexpr double kDeg = M_PI / 180.0;

void Json(httplib::Response& res, int status, const std::string& body) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  res.set_content(body, "application/json");
}

void Error(httplib::Response& res, int status, std::string_view message) {
  Json(res, status, fmt::format(R"({{"error":"{}"}})", JsonEscape(message)));
}

// A form field as a number; the whole text must parse ("nan" and "inf" do:
// the helm filter rejects them as not finite, and counts them).
bool Number(const httplib::Request& req, const char* key, double* value, std::string* problem) {
  if (!req.has_param(key)) {
    *problem = fmt::format("helm order: field '{}' is missing; expected token, rudder (deg) and rps (1/s)", key);
    return false;
  }
  const std::string text = req.get_param_value(key);
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), *value);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size()) {
    *problem = fmt::format("helm order: field '{}' is '{}'; expected a number", key, text.substr(0, 32));
    return false;
  }
  return true;
}

}  // namespace

HttpDisplayOptions HttpDisplayOptions::Parse(std::string_view text) {
  const UdpEndpoint e = UdpEndpoint::Parse(text, "--http");
  HttpDisplayOptions o;
  o.host = e.host;
  o.port = e.port;
  return o;
}

void HttpDisplayOptions::Validate() const {
  if (port < 0 || port > 65535) {
    throw ArgumentError(fmt::format("--http port {}: expected 1 to 65535", port));
  }
  if (!(update_rate >= 10 && update_rate <= 50)) {
    throw ArgumentError(fmt::format("display update rate {} Hz: expected 10 to 50 Hz", update_rate));
  }
  if (max_body < 64 || max_streams < 1 || !(helm_lapse > 0)) {
    throw ArgumentError("display limits: expected a body limit of at least 64 bytes, at least one stream and a "
                        "positive helm lapse");
  }
}

HttpDisplay::HttpDisplay(DisplayFeed& feed, DisplayInfo info, const HttpDisplayOptions& options)
    : feed_(feed),
      info_(std::move(info)),
      options_((options.Validate(), options)),
      holder_(options.helm_lapse),
      server_(std::make_unique<httplib::Server>()) {
  // One thread per open stream, and some for the other requests.
  const std::size_t threads = static_cast<std::size_t>(options_.max_streams) + 4;
  server_->new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  server_->set_payload_max_length(options_.max_body);
  server_->set_keep_alive_timeout(1);
  // Called before an error response is written (so counted before the
  // client sees it); kelvin's own handlers never answer 400, 413, 414 or 431.
  const httplib::Server::HandlerWithResponse count_errors = [this](const httplib::Request&,
                                                                   httplib::Response& res) {
    if (res.status == 413 || res.status == 414 || res.status == 431) Count(&PageCounters::oversized);
    if (res.status == 400) Count(&PageCounters::bad_requests);
    return httplib::Server::HandlerResponse::Unhandled;
  };
  server_->set_error_handler(count_errors);
  AddRoutes();
  if (options_.port == 0) {
    port_ = server_->bind_to_any_port(options_.host);
  } else {
    port_ = server_->bind_to_port(options_.host, options_.port) ? options_.port : -1;
  }
  if (port_ <= 0) {
    throw ArgumentError(fmt::format("--http {}:{}: cannot listen there (in use, or not an address of this machine)",
                                    options_.host, options_.port));
  }
  thread_ = std::thread([this] {
    server_->listen_after_bind();
    listen_returned_.store(true);
  });
  // Server::stop() does nothing before the server runs: wait until it does,
  // so that the destructor always stops it.
  while (!server_->is_running() && !listen_returned_.load()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

HttpDisplay::~HttpDisplay() {
  stopping_.store(true);
  server_->stop();
  if (thread_.joinable()) thread_.join();
}

std::string HttpDisplay::url() const { return fmt::format("http://{}:{}/", options_.host, port_); }

PageCounters HttpDisplay::counters() const {
  std::lock_guard<std::mutex> lock(counters_mutex_);
  return counters_;
}

void HttpDisplay::Count(long PageCounters::*counter) {
  std::lock_guard<std::mutex> lock(counters_mutex_);
  ++(counters_.*counter);
}

std::string HttpDisplay::StateText() {
  return StateJson(feed_.Snapshot(), info_, holder_.held(MonotonicNanoseconds()), counters());
}

void HttpDisplay::AddRoutes() {
  httplib::Server& s = *server_;
  s.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(DisplayPageHtml()), "text/html; charset=utf-8");
  });
  s.Get("/display.js", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(DisplayPageScript()), "text/javascript; charset=utf-8");
  });
  s.Get("/state", [this](const httplib::Request&, httplib::Response& res) { Json(res, 200, StateText()); });
  s.Get("/track", [this](const httplib::Request&, httplib::Response& res) {
    const std::vector<TrackPoint> track = feed_.Track();
    Json(res, 200, TrackJson(track));
  });
  s.Get("/stream", [this](const httplib::Request& req, httplib::Response& res) { Stream(req, res); });
  s.Post("/helm/claim", [this](const httplib::Request&, httplib::Response& res) { Claim(res); });
  s.Post("/helm/release", [this](const httplib::Request& req, httplib::Response& res) { Release(req, res); });
  s.Post("/helm", [this](const httplib::Request& req, httplib::Response& res) { Helm(req, res); });
}

void HttpDisplay::Stream(const httplib::Request&, httplib::Response& res) {
  {
    std::lock_guard<std::mutex> lock(counters_mutex_);
    if (counters_.streams_open >= options_.max_streams) {
      ++counters_.streams_refused;
      res.status = 503;
      res.set_content(fmt::format("at most {} pages may watch at once\n", options_.max_streams), "text/plain");
      return;
    }
    ++counters_.streams_open;
  }
  res.set_header("Cache-Control", "no-store");
  const auto period = std::chrono::duration<double>(1.0 / options_.update_rate);
  res.set_chunked_content_provider(
      "text/event-stream",
      [this, period](std::size_t offset, httplib::DataSink& sink) {
        if (offset > 0) std::this_thread::sleep_for(period);
        if (stopping_.load()) {
          sink.done();
          return true;
        }
        const std::string event = "data: " + StateText() + "\n\n";
        return sink.write(event.data(), event.size());
      },
      [this](bool) {
        std::lock_guard<std::mutex> lock(counters_mutex_);
        --counters_.streams_open;
      });
}

void HttpDisplay::Claim(httplib::Response& res) {
  const std::optional<std::string> token = holder_.Claim(MonotonicNanoseconds());
  if (!token) {
    Error(res, 409, "another page holds the helm");
    return;
  }
  Json(res, 200, fmt::format(R"({{"token":"{}"}})", *token));
}

void HttpDisplay::Release(const httplib::Request& req, httplib::Response& res) {
  if (!holder_.Release(req.get_param_value("token"), MonotonicNanoseconds())) {
    Count(&PageCounters::not_holder);
    Error(res, 403, "this page does not hold the helm");
    return;
  }
  Json(res, 200, R"({"released":true})");
}

void HttpDisplay::Helm(const httplib::Request& req, httplib::Response& res) {
  if (!holder_.Holds(req.get_param_value("token"), MonotonicNanoseconds())) {
    Count(&PageCounters::not_holder);
    Error(res, 403, "this page does not hold the helm: claim it first (POST /helm/claim)");
    return;
  }
  double rudder = 0, rps = 0;
  std::string problem;
  if (!Number(req, "rudder", &rudder, &problem) || !Number(req, "rps", &rps, &problem)) {
    Count(&PageCounters::malformed);
    Error(res, 422, problem);
    return;
  }
  kelvin::helm_command_t command{};
  command.utime = RealtimeMicroseconds();
  command.source_id = info_.helm_source;
  command.rudder_order = rudder * kDeg;
  command.rps_order = rps;
  if (!feed_.QueueHelm(command)) {
    Count(&PageCounters::inbox_full);
    Error(res, 503, "helm orders arrive faster than the bridge takes them; dropped");
    return;
  }
  Count(&PageCounters::helm_queued);
  Json(res, 200, R"({"queued":true})");
}

}  // namespace kelvin::bridge
