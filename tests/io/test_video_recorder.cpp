// The video of a run: option checks, a short walking run rendered and encoded (frame count by
// ffprobe, decoded frames not blank and showing the robot), and no file left by an unfinished video.
#include "io/video_recorder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "io/yaml_reader.hpp"
#include "sim/simulation.hpp"
#include "studies/scenario_runner.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace biped {
namespace {

using test::fresh_dir;

std::string command_output(const std::string& command) {
  FILE* p = popen(command.c_str(), "r");
  std::string out;
  if (!p) return out;
  char buf[1 << 16];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof(buf), p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
}

Scenario lola_walk(double duration) {
  Scenario s = load_scenario(data_directory() + "/config/scenarios/lola-walk.yaml", {});
  s.duration = duration;
  return s;
}

// One decoded RGB frame.
struct Frame {
  int width, height;
  const unsigned char* rgb;
  const unsigned char* at(int x, int y) const { return rgb + 3 * (y * width + x); }
};

double luminance_stddev(const Frame& f) {
  double sum = 0.0, sum2 = 0.0;
  const int n = f.width * f.height;
  for (int i = 0; i < n; ++i) {
    const unsigned char* p = f.rgb + 3 * i;
    const double y = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
    sum += y;
    sum2 += y * y;
  }
  const double mean = sum / n;
  return std::sqrt(std::max(0.0, sum2 / n - mean * mean));
}

// Share of grey pixels (the robot's colour; the ground is warm, the sky blue) in a column band.
double grey_share(const Frame& f, int x0, int x1, int y0, int y1) {
  int grey = 0, all = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const unsigned char* p = f.at(x, y);
      grey += std::abs(p[0] - p[2]) < 10 && std::abs(p[0] - p[1]) < 10;
      ++all;
    }
  }
  return static_cast<double>(grey) / all;
}

TEST(VideoOptions, BadOptionsNameTheOption) {
  const fs::path dir = fresh_dir("video-options");
  VideoOptions o;
  o.path = (dir / "run.avi").string();
  EXPECT_THROW(check_video_options(o), InputError);
  try {
    check_video_options(o);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--video"), std::string::npos) << e.what();
  }
  o.path = (dir / "run.mp4").string();
  EXPECT_NO_THROW(check_video_options(o));
  o.width = 641;
  EXPECT_THROW(check_video_options(o), InputError);
  o.width = 640;
  o.fps = 0.0;
  EXPECT_THROW(check_video_options(o), InputError);
  o.fps = 30.0;
  o.path = (dir / "new" / "folder" / "run.mp4").string();
  EXPECT_NO_THROW(check_video_options(o));
  EXPECT_TRUE(fs::is_directory(dir / "new" / "folder"));
  std::ofstream(dir / "plain-file") << "x";
  o.path = (dir / "plain-file" / "run.mp4").string();
  EXPECT_THROW(check_video_options(o), InputError);

  parse_video_size("320x240", o);
  EXPECT_EQ(o.width, 320);
  EXPECT_EQ(o.height, 240);
  EXPECT_THROW(parse_video_size("320", o), InputError);
  EXPECT_THROW(parse_video_size("320x240x1", o), InputError);
  fs::remove_all(dir);
}

TEST(VideoRecorder, AWalkingRunHasOneFramePerPeriodAndShowsTheRobot) {
  const fs::path dir = fresh_dir("video-run");
  const Scenario scenario = lola_walk(1.0);
  VideoOptions video;
  video.path = (dir / "walk.mp4").string();
  const ScenarioResult result = run_scenario(scenario, make_run_config(scenario), "", nullptr, &video);
  ASSERT_TRUE(fs::exists(video.path));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << "temporary file left";
  EXPECT_EQ(result.summary["video"]["frames"].get<int>(), 30);

  const std::string counted = command_output("ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                                             "stream=nb_read_frames -of csv=p=0 " + video.path);
  EXPECT_NEAR(std::atoi(counted.c_str()), scenario.duration * video.fps, 1.0) << counted;

  const std::vector<int> picked = {0, 15, 29};
  const std::string raw = command_output("ffmpeg -v error -i " + video.path +
                                         " -vf \"select=eq(n\\,0)+eq(n\\,15)+eq(n\\,29)\" -vsync 0 "
                                         "-f rawvideo -pix_fmt rgb24 -");
  const std::size_t frame_bytes = static_cast<std::size_t>(3 * video.width * video.height);
  ASSERT_EQ(raw.size(), picked.size() * frame_bytes);
  for (std::size_t k = 0; k < picked.size(); ++k) {
    const Frame f{video.width, video.height, reinterpret_cast<const unsigned char*>(raw.data()) + k * frame_bytes};
    EXPECT_GT(luminance_stddev(f), 20.0) << "frame " << picked[k] << " is (nearly) uniform";
    // The camera follows the upper body: the robot fills the middle of the picture, not its sides.
    const int w = f.width, h = f.height;
    const double centre = grey_share(f, 2 * w / 5, 3 * w / 5, h / 5, 4 * h / 5);
    const double sides = 0.5 * (grey_share(f, 0, w / 5, h / 5, 4 * h / 5) + grey_share(f, 4 * w / 5, w, h / 5, 4 * h / 5));
    EXPECT_GT(centre, 0.2) << "frame " << picked[k];
    EXPECT_LT(sides, 0.05) << "frame " << picked[k];
  }
  fs::remove_all(dir);
}

// Each frame names the controller's state (and the simulated time) at its top left: the same
// robot pose with another state differs there and nowhere else.
TEST(VideoRecorder, TheOverlayShowsTheControllersStateAtTheTopLeft) {
  const fs::path dir = fresh_dir("video-overlay");
  const Scenario scenario = lola_walk(1.0);
  const RunConfig config = make_run_config(scenario);
  const RobotModel model = load_controller_model(config);
  Simulation sim(config.sim, model);
  VideoOptions video;
  video.path = (dir / "overlay.mp4").string();
  VideoRecorder recorder(sim, video);
  SensorData sensors(model.num_joints());
  const JointCommand command(model.num_joints());
  ControllerStatus status;
  std::vector<unsigned char> walking, safe_stop;
  status.state = "walking";
  recorder.record(sim, sensors, command, status, 0.0);
  recorder.render(sim, walking);  // a first picture: it differs from later ones of the same state
  recorder.render(sim, walking);
  status.state = "safe_stop";
  recorder.record(sim, sensors, command, status, 0.0);
  recorder.render(sim, safe_stop);
  ASSERT_EQ(walking.size(), safe_stop.size());
  int inside = 0, outside = 0, x_max = 0, y_max = 0;
  for (int y = 0; y < video.height; ++y) {
    for (int x = 0; x < video.width; ++x) {
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * video.width + x);
      if (std::equal(&walking[i], &walking[i] + 3, &safe_stop[i])) continue;
      (x < video.width / 3 && y < video.height / 5 ? inside : outside) += 1;
      x_max = std::max(x_max, x);
      y_max = std::max(y_max, y);
    }
  }
  EXPECT_GT(inside, 50) << "the state's text changed";
  EXPECT_EQ(outside, 0) << "differences reach x = " << x_max << ", y = " << y_max;
  fs::remove_all(dir);
}

TEST(VideoRecorder, AnUnfinishedVideoLeavesNoFile) {
  const fs::path dir = fresh_dir("video-unfinished");
  const Scenario scenario = lola_walk(1.0);
  const RunConfig config = make_run_config(scenario);
  const RobotModel model = load_controller_model(config);
  Simulation sim(config.sim, model);
  VideoOptions video;
  video.path = (dir / "cut.mp4").string();
  video.width = 160;
  video.height = 120;
  {
    VideoRecorder recorder(sim, video);
    recorder.cycle_start(sim);
    EXPECT_EQ(recorder.frames(), 1);
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace biped
