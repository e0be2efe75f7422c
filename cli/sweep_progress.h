// The progress of a long sweep on stderr: a bar with the rate and the time left on a terminal,
// and in a batch log (stderr not a terminal) one line every few seconds.
#pragma once

#include <chrono>
#include <string>

namespace stairplan::cli {

class SweepProgressReport {
 public:
  /// `label` heads each line (e.g. the robot); `already` points were done before this run (resume).
  SweepProgressReport(std::string label, int total, int already, bool terminal);
  /// Called with the points done by this run so far (serialised by the caller).
  void Update(int done);

 private:
  std::string Line(int done, double seconds) const;

  std::string label_;
  int total_ = 0;
  int already_ = 0;
  bool terminal_ = false;
  std::chrono::steady_clock::time_point start_;
  double last_line_s_ = 0.0;
};

}  // namespace stairplan::cli
