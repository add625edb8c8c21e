#pragma once
// Offscreen video of a run: renders the simulator's state with MuJoCo's renderer in a headless
// OpenGL context (EGL, Mesa surfaceless) at a fixed rate of simulated time and pipes the frames to
// ffmpeg, which writes an H.264 (or MPEG-4 part 2) .mp4. The file is whole or not at all.
#include <sys/types.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/closed_loop.hpp"

namespace biped {

struct VideoOptions {
  std::string path;  // the .mp4 to write
  double fps = 30.0; // frames per second of simulated time (and of the video)
  int width = 640;   // [pixels], even (H.264 with 4:2:0 chroma needs even sizes)
  int height = 480;
};

// The machine cannot render or encode (no headless OpenGL context, no ffmpeg, ffmpeg failed).
class VideoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Checks the options before anything runs: a .mp4 name in a writable folder (created if
// missing), a size and a rate in range. Throws InputError naming the command-line option.
void check_video_options(const VideoOptions& options);

// Parses "WxH" (e.g. "640x480") into options; throws InputError naming --video-size.
void parse_video_size(const std::string& text, VideoOptions& options);

class VideoRecorder final : public RunObserver {
 public:
  // Creates the GL context and starts ffmpeg on a temporary file; throws VideoError when either
  // is impossible, so a run with a video fails before it simulates.
  VideoRecorder(const Simulation& sim, const VideoOptions& options);
  ~VideoRecorder() override;
  VideoRecorder(const VideoRecorder&) = delete;
  VideoRecorder& operator=(const VideoRecorder&) = delete;

  // Keeps the controller's state for the frames' overlay.
  void record(const Simulation&, const SensorData&, const JointCommand&, const ControllerStatus& status, double) override {
    state_ = status.state;
  }
  // Renders every frame that falls due at the simulator's current time.
  void cycle_start(const Simulation& sim) override;

  // Renders the simulator's state now into rgb (width × height × 3 bytes, top row first), with the
  // simulated time and the controller's last recorded state written at the top left.
  void render(const Simulation& sim, std::vector<unsigned char>& rgb);

  // Ends the stream, waits for ffmpeg and renames the file to its final name; throws VideoError.
  void commit();

  int frames() const { return frames_; }
  double render_seconds() const { return render_seconds_; }  // wall time in render() so far
  const std::string& codec() const { return codec_; }

 private:
  struct Gl;
  void write_frame();
  // Closes the pipe and waits for ffmpeg; returns its wait status.
  int stop_encoder();

  VideoOptions options_;
  std::string temp_path_;
  std::string codec_;
  std::unique_ptr<Gl> gl_;
  std::vector<unsigned char> frame_;
  std::string state_;  // the controller's FSM state at the last record()
  int frames_ = 0;
  double render_seconds_ = 0.0;
  int pipe_fd_ = -1;
  pid_t encoder_pid_ = -1;
  bool committed_ = false;
};

}  // namespace biped
