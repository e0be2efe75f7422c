#include "cli/sweep_progress.h"

#include <cstdio>

namespace stairplan::cli {
namespace {

// A batch log needs a line often enough to show the job is alive, rarely enough to stay readable.
constexpr double kLogInterval = 5.0;  // [s]

std::string Duration(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  char buffer[32];
  if (s >= 3600) {
    std::snprintf(buffer, sizeof(buffer), "%ldh%02ldm", s / 3600, s / 60 % 60);
  } else {
    std::snprintf(buffer, sizeof(buffer), "%ldm%02lds", s / 60, s % 60);
  }
  return buffer;
}

}  // namespace

SweepProgressReport::SweepProgressReport(std::string label, int total, int already, bool terminal)
    : label_(std::move(label)), total_(total), already_(already), terminal_(terminal),
      start_(std::chrono::steady_clock::now()) {}

std::string SweepProgressReport::Line(int done, double seconds) const {
  const int finished = already_ + done, left = total_ - finished;
  const double rate = seconds > 0 ? done / seconds : 0.0;
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), "%d/%d points, %.2f points/s, ETA %s", finished, total_, rate,
                rate > 0 ? Duration(left / rate).c_str() : "?");
  return buffer;
}

void SweepProgressReport::Update(int done) {
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const bool last = already_ + done >= total_;
  if (terminal_) {
    const int width = 30, filled = total_ > 0 ? width * (already_ + done) / total_ : width;
    std::fprintf(stderr, "\r%s[%s%s] %s ", label_.c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(width - filled), '.').c_str(), Line(done, seconds).c_str());
    if (last) std::fprintf(stderr, "\n");
    return;
  }
  if (!last && seconds - last_line_s_ < kLogInterval) return;
  last_line_s_ = seconds;
  std::fprintf(stderr, "%ssweep: %s\n", label_.c_str(), Line(done, seconds).c_str());
}

}  // namespace stairplan::cli
