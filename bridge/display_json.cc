#include "bridge/display_json.h"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

namespace kelvin::bridge {

namespace {

// Shortest text that reads back to the same double; null if not finite.
std::string Num(double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string("null"); }

const char* PhaseName(std::int8_t phase) {
  switch (phase) {
    case kelvin::ship_state_t::PHASE_APPROACH: return "approach";
    case kelvin::ship_state_t::PHASE_EXECUTE: return "execute";
    case kelvin::ship_state_t::PHASE_STEADY: return "steady";
    case kelvin::ship_state_t::PHASE_FINISHED: return "finished";
    case kelvin::ship_state_t::PHASE_FREE: return "free";
  }
  return "unknown";
}

const char* EventName(std::int8_t kind) {
  switch (kind) {
    case kelvin::maneuver_event_t::START: return "start";
    case kelvin::maneuver_event_t::EXECUTE: return "execute";
    case kelvin::maneuver_event_t::OVERSHOOT: return "overshoot";
    case kelvin::maneuver_event_t::STOP: return "stop";
  }
  return "unknown";
}

void AppendState(std::string& out, const kelvin::ship_state_t& st) {
  fmt::format_to(std::back_inserter(out),
                 R"("state":{{"seq":{},"utime":{},"t":{},"x":{},"y":{},"latitude":{},"longitude":{},"heading":{},)"
                 R"("u":{},"v":{},"r":{},"speed_over_ground":{},"course_over_ground":{},"drift_angle":{},)"
                 R"("rudder_angle":{},"rudder_order":{},"propeller_rps":{},"propeller_rps_order":{},"phase":"{}"}})",
                 st.seq, st.utime, Num(st.t), Num(st.x), Num(st.y), Num(st.latitude), Num(st.longitude),
                 Num(st.heading), Num(st.u), Num(st.v), Num(st.r), Num(st.speed_over_ground),
                 Num(st.course_over_ground), Num(st.drift_angle), Num(st.rudder_angle), Num(st.rudder_order),
                 Num(st.propeller_rps), Num(st.propeller_rps_order), PhaseName(st.maneuver_phase));
}

void AppendEvents(std::string& out, const DisplaySnapshot& s) {
  fmt::format_to(std::back_inserter(out), R"("events_total":{},"events":[)", s.events_total);
  for (int i = 0; i < s.n_events; ++i) {
    const auto& e = s.events[static_cast<std::size_t>(i)];
    fmt::format_to(std::back_inserter(out),
                   R"({}{{"seq":{},"kind":"{}","index":{},"t":{},"heading":{},"heading_change":{},"overshoot":{}}})",
                   i ? "," : "", e.seq, EventName(e.kind), e.index, Num(e.t), Num(e.heading), Num(e.heading_change),
                   Num(e.overshoot));
  }
  out += "]";
}

void AppendCounters(std::string& out, const HelmCounters& h, bool held, const PageCounters& p) {
  fmt::format_to(std::back_inserter(out),
                 R"("helm":{{"held":{},"received":{},"accepted":{},"clamped":{},"rejected":{},"malformed":{},)"
                 R"("not_finite":{},"out_of_range":{},"stale":{},"future":{},"unknown_source":{}}},)"
                 R"("page":{{"helm_queued":{},"not_holder":{},"malformed":{},"oversized":{},"bad_requests":{},)"
                 R"("inbox_full":{},"streams_refused":{},"streams_open":{}}})",
                 held, h.received, h.accepted, h.clamped, h.rejected(), h.malformed, h.not_finite, h.out_of_range,
                 h.stale, h.future, h.unknown_source, p.helm_queued, p.not_holder, p.malformed, p.oversized,
                 p.bad_requests, p.inbox_full, p.streams_refused, p.streams_open);
}

}  // namespace

std::string JsonEscape(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          out += fmt::format("\\u{:04x}", static_cast<unsigned>(c));
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string StateJson(const DisplaySnapshot& s, const DisplayInfo& info, bool helm_held, const PageCounters& page) {
  std::string out = fmt::format(
      R"({{"ship":"{}","script":"{}","origin":[{},{}],"helm_source":{},"derivatives":{{"checked":{},"message":"{}"}},)",
      JsonEscape(info.ship), JsonEscape(info.script), Num(info.origin_latitude), Num(info.origin_longitude),
      info.helm_source, info.derivatives_checked, JsonEscape(info.derivatives));
  if (s.has_state) {
    AppendState(out, s.state);
  } else {
    out += R"("state":null)";
  }
  out += ",";
  AppendEvents(out, s);
  out += ",";
  AppendCounters(out, s.helm, helm_held, page);
  out += "}";
  return out;
}

std::string TrackJson(std::span<const TrackPoint> track) {
  std::string out;
  const auto column = [&](const char* name, double TrackPoint::*member) {
    fmt::format_to(std::back_inserter(out), R"({}"{}":[)", out.empty() ? "{" : ",", name);
    for (std::size_t i = 0; i < track.size(); ++i) {
      if (i) out += ',';
      out += Num(track[i].*member);
    }
    out += ']';
  };
  column("t", &TrackPoint::t);
  column("x", &TrackPoint::x);
  column("y", &TrackPoint::y);
  out += '}';
  return out;
}

}  // namespace kelvin::bridge
