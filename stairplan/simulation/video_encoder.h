// Frames to an mp4 or to numbered PNGs through Debian's ffmpeg program, fed raw RGB over a pipe.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace stairplan {

/// What the frames become.
enum class VideoOutput { kMp4, kPngFrames };

/// Rendered frames into an MP4 or PNG files through ffmpeg.
class VideoEncoder {
 public:
  /// Starts ffmpeg writing `path` (kPngFrames: a directory, frames frame_00000.png ...) from
  /// width x height RGB frames shown at `fps`. Throws std::runtime_error when ffmpeg cannot start.
  VideoEncoder(VideoOutput output, const std::string& path, int width, int height, double fps);
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  /// One frame, rows from the top; throws std::runtime_error when ffmpeg has gone.
  void Write(const std::vector<unsigned char>& rgb);
  /// Waits for ffmpeg; throws std::runtime_error naming the output when it failed.
  void Finish();
  /// Frames written so far.
  int frames() const { return frames_; }

 private:
  std::FILE* pipe_ = nullptr;
  std::string path_;
  std::size_t frame_bytes_ = 0;
  int frames_ = 0;
};

}  // namespace stairplan
