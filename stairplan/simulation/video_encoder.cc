#include "stairplan/simulation/video_encoder.h"

#include <sstream>
#include <stdexcept>

namespace stairplan {
namespace {

// A shell word: single-quoted, with embedded single quotes closed, escaped and reopened.
std::string ShellQuoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

VideoEncoder::VideoEncoder(VideoOutput output, const std::string& path, int width, int height, double fps)
    : path_(path), frame_bytes_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
  std::ostringstream command;
  command << "ffmpeg -nostdin -loglevel error -y -f rawvideo -pix_fmt rgb24 -s " << width << "x" << height
          << " -framerate " << fps << " -i - ";
  if (output == VideoOutput::kMp4) {
    // yuv420p: what players expect; even sizes are MuJoCo's default 640 x 480.
    command << "-c:v libx264 -preset veryfast -crf 23 -pix_fmt yuv420p -movflags +faststart " << ShellQuoted(path);
  } else {
    command << ShellQuoted(path + "/frame_%05d.png");
  }
  pipe_ = popen(command.str().c_str(), "w");
  if (pipe_ == nullptr) throw std::runtime_error(path + ": cannot start ffmpeg");
}

VideoEncoder::~VideoEncoder() {
  if (pipe_ != nullptr) pclose(pipe_);
}

void VideoEncoder::Write(const std::vector<unsigned char>& rgb) {
  if (rgb.size() != frame_bytes_) throw std::invalid_argument(path_ + ": a frame of the wrong size");
  if (pipe_ == nullptr || std::fwrite(rgb.data(), 1, rgb.size(), pipe_) != rgb.size()) {
    throw std::runtime_error(path_ + ": ffmpeg stopped taking frames (is it installed? scripts/setup.sh installs it)");
  }
  ++frames_;
}

void VideoEncoder::Finish() {
  if (pipe_ == nullptr) return;
  const int status = pclose(pipe_);
  pipe_ = nullptr;
  if (status != 0) {
    throw std::runtime_error(path_ + ": ffmpeg failed (exit status " + std::to_string(status) +
                             "; is it installed? scripts/setup.sh installs it)");
  }
}

}  // namespace stairplan
