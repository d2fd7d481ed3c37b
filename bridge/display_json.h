// The JSON documents of the browser display: the state update sent over
// server-sent events (and by GET /state), and the thinned track. Values in
// SI units and radians, as in ship_state_t; the page converts for display.
#pragma once

#include <span>
#include <string>

#include "bridge/display_feed.h"

namespace kelvin::bridge {

// What does not change during a run.
struct DisplayInfo {
  std::string ship;
  std::string script;          // empty: helm
  bool derivatives_checked = false;
  std::string derivatives;     // the assessment's message
  double origin_latitude = 0, origin_longitude = 0;  // deg
  int helm_source = 0;         // source_id of the page's helm orders
};

// Counters of the HTTP side.
struct PageCounters {
  long helm_queued = 0;       // page orders handed to the helm filter
  long not_holder = 0;        // helm orders (and releases) from a page without the helm
  long malformed = 0;         // requests whose parameters do not parse
  long oversized = 0;         // bodies or headers beyond the limits (413, 414, 431)
  long bad_requests = 0;      // requests httplib could not parse (400)
  long inbox_full = 0;        // page orders dropped because the loop had not drained the previous ones
  long streams_refused = 0;   // event streams beyond the limit
  long streams_open = 0;
};

std::string JsonEscape(std::string_view text);
std::string StateJson(const DisplaySnapshot& s, const DisplayInfo& info, bool helm_held, const PageCounters& page);
std::string TrackJson(std::span<const TrackPoint> track);

}  // namespace kelvin::bridge
