#include "data/report/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace kelvin {

std::string FormatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--";
  if (seconds < 60) return fmt::format("{:.1f}s", seconds);
  const long s = std::lround(seconds);
  if (s < 3600) return fmt::format("{}m{:02d}s", s / 60, static_cast<int>(s % 60));
  return fmt::format("{}h{:02d}m", s / 3600, static_cast<int>((s % 3600) / 60));
}

Progress::Progress(double total, Options options)
    : total_(std::max(total, 1e-300)), opt_(std::move(options)) {
  terminal_ = opt_.stream && ::isatty(::fileno(opt_.stream));
  start_ = std::chrono::steady_clock::now();
  last_draw_ = start_ - std::chrono::hours(1);
  next_plain_fraction_ = opt_.plain_every;
}

double Progress::elapsed_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double Progress::eta_seconds(double done) const {
  if (done <= 0) return -1.0;
  const double t = elapsed_seconds();
  return t * (total_ - done) / done;
}

void Progress::Update(double done, const std::string& status) {
  if (!opt_.enabled || finished_) return;
  done_ = done;
  if (elapsed_seconds() < opt_.delay_seconds) return;
  const double fraction = std::clamp(done / total_, 0.0, 1.0);
  if (terminal_) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_draw_).count() < opt_.redraw_seconds) return;
    last_draw_ = now;
    Print(done, status, false);
  } else if (fraction + 1e-12 >= next_plain_fraction_) {
    while (next_plain_fraction_ <= fraction + 1e-12) next_plain_fraction_ += opt_.plain_every;
    Print(done, status, false);
  }
}

void Progress::Finish(const std::string& status) {
  if (!opt_.enabled || finished_) return;
  // A run that ended early (a steady criterion, a finished maneuver) reports what it did.
  if (printed_ || elapsed_seconds() >= opt_.delay_seconds) Print(done_ >= 0 ? done_ : total_, status, true);
  finished_ = true;
}

void Progress::Print(double done, const std::string& status, bool final_line) {
  const double t = elapsed_seconds();
  const double pct = 100.0 * std::clamp(done / total_, 0.0, 1.0);
  const double rate = t > 0 ? done / t : 0.0;
  std::string line;
  if (final_line) {
    line = fmt::format("{}: done {:.0f} {} in {} ({:.3g} {}/s)", opt_.label, done, opt_.unit, FormatDuration(t),
                       rate, opt_.unit);
  } else {
    line = fmt::format("{}: {:5.1f}%  {:.0f}/{:.0f} {}  {:.3g} {}/s  ETA {}", opt_.label, pct, done, total_,
                       opt_.unit, rate, opt_.unit, FormatDuration(eta_seconds(done)));
  }
  if (!status.empty()) line += "  " + status;
  if (terminal_) {
    fmt::print(opt_.stream, "\r\033[K{}{}", line, final_line ? "\n" : "");
  } else {
    fmt::print(opt_.stream, "{}\n", line);
  }
  std::fflush(opt_.stream);
  printed_ = true;
}

}  // namespace kelvin
