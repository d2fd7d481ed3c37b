// Progress display for long runs: percentage, rate and ETA on one line that
// redraws in a terminal, and plain periodic log lines when stdout is a pipe
// or a file (CI logs, nohup).
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace kelvin {

class Progress {
 public:
  struct Options {
    std::string label = "run";
    std::string unit = "steps";
    // Plain mode prints a line each time this fraction of the work is done.
    double plain_every = 0.1;
    // Redraw interval in a terminal.
    double redraw_seconds = 0.2;
    // Nothing is printed until the run has taken this long, so that short
    // runs stay quiet; the final line appears only if something was printed.
    double delay_seconds = 1.0;
    bool enabled = true;
    std::FILE* stream = stdout;
  };

  Progress(double total, Options options);
  // Reports `done` units of `total`, with an optional free-text status
  // (residuals, Courant number, ...).
  void Update(double done, const std::string& status = "");
  // Prints the final line (100%, elapsed time).
  void Finish(const std::string& status = "");

  double elapsed_seconds() const;
  // Estimated seconds left; negative when unknown.
  double eta_seconds(double done) const;
  bool is_terminal() const { return terminal_; }

 private:
  void Print(double done, const std::string& status, bool final_line);

  double total_;
  Options opt_;
  bool terminal_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  double next_plain_fraction_ = 0.0;
  bool finished_ = false;
  double done_ = -1.0;  // the last Update's count (-1: none; Finish then reports the total)
  bool printed_ = false;
};

// "1h02m", "3m05s", "12.3s".
std::string FormatDuration(double seconds);

}  // namespace kelvin
