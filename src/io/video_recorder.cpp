#include "io/video_recorder.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <fcntl.h>
#include <mujoco/mujoco.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "io/yaml_reader.hpp"
#include "sim/simulation.hpp"

extern char** environ;

namespace fs = std::filesystem;

namespace biped {
namespace {

// A 3/4 view from the front left, the robot's whole height in the picture.
constexpr double kCameraAzimuthDeg = 215.0;
constexpr double kCameraElevationDeg = -12.0;
constexpr double kCameraDistance = 3.6;             // [m]
constexpr double kLookatHeightShare = 0.8;          // of the upper body's height at the first frame
constexpr double kCameraFollowTimeConstant = 0.4;   // [s] smooths the step-to-step sway out of the view
// Software rendering costs (Mesa llvmpipe, 640×480, measured): MuJoCo's default 4× multisampling
// doubles the time of a frame (≈ 140 against 70 ms) and looks the same after H.264; its default
// 4096² shadow map costs ≈ 20 % more than 2048², which looks the same here.
constexpr int kMultisamples = 0;
constexpr int kShadowMapSize = 2048;

std::string egl_error(const char* what) {
  char code[32];
  std::snprintf(code, sizeof(code), "0x%04x", eglGetError());
  return std::string(what) + " failed (EGL error " + code + ")";
}

// Lists ffmpeg's encoders; empty when ffmpeg cannot be run.
std::string ffmpeg_encoders() {
  FILE* p = popen("ffmpeg -hide_banner -encoders 2>/dev/null", "r");
  if (!p) return "";
  std::string out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof(buf), p)) > 0) out.append(buf, n);
  return pclose(p) == 0 ? out : "";
}

}  // namespace

// The headless GL context and MuJoCo's renderer, with a copy of the simulator's model (the
// offscreen size lives in the model) and a data of its own (the simulator's stays untouched).
struct VideoRecorder::Gl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;
  mjModel* model = nullptr;
  mjData* data = nullptr;
  mjvScene scene;
  mjrContext context_mj;
  mjvCamera camera;
  mjvOption option;
  bool scene_made = false, context_made = false;
  int tracked_body = 0;
  double lookat_z = 0.0;
  bool camera_placed = false;
  std::vector<unsigned char> bottom_up;

  Gl(const mjModel* sim_model, const VideoOptions& o) {
    try {
      make_egl_context();
      make_renderer(sim_model, o);
    } catch (...) {
      release();
      throw;
    }
    mjv_defaultOption(&option);
    mjv_defaultCamera(&camera);
    camera.type = mjCAMERA_FREE;
    camera.azimuth = kCameraAzimuthDeg;
    camera.elevation = kCameraElevationDeg;
    camera.distance = kCameraDistance;
    const int upper_body = mj_name2id(model, mjOBJ_BODY, "upper_body");
    tracked_body = upper_body >= 0 ? upper_body : 1;  // else the floating base
    bottom_up.resize(static_cast<std::size_t>(3 * o.width * o.height));
  }

  ~Gl() { release(); }

  void make_renderer(const mjModel* sim_model, const VideoOptions& o) {
    model = mj_copyModel(nullptr, sim_model);
    model->vis.global.offwidth = o.width;
    model->vis.global.offheight = o.height;
    model->vis.quality.shadowsize = kShadowMapSize;
    model->vis.quality.offsamples = kMultisamples;
    data = mj_makeData(model);
    mjv_defaultScene(&scene);
    mjv_makeScene(model, &scene, 2000);
    scene_made = true;
    mjr_defaultContext(&context_mj);
    // The overlay's font grows with the picture (MuJoCo's scales: 100 %, 150 %, 200 %).
    mjr_makeContext(model, &context_mj, o.height >= 960 ? mjFONTSCALE_200 : o.height >= 720 ? mjFONTSCALE_150 : mjFONTSCALE_100);
    context_made = true;
    mjr_setBuffer(mjFB_OFFSCREEN, &context_mj);
    if (context_mj.currentBuffer != mjFB_OFFSCREEN || context_mj.offWidth != o.width ||
        context_mj.offHeight != o.height) {
      throw VideoError("--video: the OpenGL context cannot hold a " + std::to_string(o.width) + "x" +
                       std::to_string(o.height) + " offscreen buffer");
    }
  }

  void release() {
    if (context_made) mjr_freeContext(&context_mj);
    if (scene_made) mjv_freeScene(&scene);
    if (data) mj_deleteData(data);
    if (model) mj_deleteModel(model);
    context_made = scene_made = false;
    data = nullptr;
    model = nullptr;
    release_egl();
  }

  // Mesa's surfaceless platform needs no display server and no GPU; a 1×1 pbuffer keeps the
  // context current on EGL implementations without surfaceless contexts. MuJoCo draws into its
  // own framebuffer object, so the pbuffer's size does not matter.
  void make_egl_context() {
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display) display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (display == EGL_NO_DISPLAY) throw VideoError("--video: no headless OpenGL: no EGL display (needs Mesa's libegl-mesa0)");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
      display = EGL_NO_DISPLAY;
      throw VideoError("--video: no headless OpenGL: " + egl_error("eglInitialize"));
    }
    const EGLint config_attributes[] = {EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_DEPTH_SIZE, 24,
                                        EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                        EGL_NONE};
    EGLConfig config;
    EGLint count = 0;
    if (!eglChooseConfig(display, config_attributes, &config, 1, &count) || count < 1) {
      throw VideoError("--video: no headless OpenGL: no EGL configuration with desktop OpenGL and a pbuffer");
    }
    const EGLint pbuffer_attributes[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    surface = eglCreatePbufferSurface(display, config, pbuffer_attributes);
    if (surface == EGL_NO_SURFACE) throw VideoError("--video: no headless OpenGL: " + egl_error("eglCreatePbufferSurface"));
    // MuJoCo's renderer uses fixed-function (compatibility profile) OpenGL, not OpenGL ES.
    if (!eglBindAPI(EGL_OPENGL_API)) throw VideoError("--video: no headless OpenGL: " + egl_error("eglBindAPI(EGL_OPENGL_API)"));
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
    if (context == EGL_NO_CONTEXT) throw VideoError("--video: no headless OpenGL: " + egl_error("eglCreateContext"));
    if (!eglMakeCurrent(display, surface, surface, context)) {
      throw VideoError("--video: no headless OpenGL: " + egl_error("eglMakeCurrent"));
    }
    // mjr_makeContext ends the process on a GL it cannot use, so check first: MuJoCo needs
    // framebuffer objects, core from OpenGL 3.0 on.
    using GetString = const GLubyte* (*)(GLenum);
    auto get_string = reinterpret_cast<GetString>(eglGetProcAddress("glGetString"));
    const char* version = get_string ? reinterpret_cast<const char*>(get_string(GL_VERSION)) : nullptr;
    if (!version || std::atoi(version) < 3) {
      throw VideoError(std::string("--video: the headless OpenGL context is too old for MuJoCo's renderer (version ") +
                       (version ? version : "unknown") + ", needs 3.0)");
    }
  }

  void release_egl() {
    if (display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
    eglTerminate(display);
    display = EGL_NO_DISPLAY;
  }

  void place_camera(double fps) {
    const double* body = data->xpos + 3 * tracked_body;
    if (!camera_placed) {
      lookat_z = kLookatHeightShare * body[2];
      camera.lookat[0] = body[0];
      camera.lookat[1] = body[1];
      camera_placed = true;
    }
    const double blend = 1.0 - std::exp(-1.0 / (fps * kCameraFollowTimeConstant));
    camera.lookat[0] += blend * (body[0] - camera.lookat[0]);
    camera.lookat[1] += blend * (body[1] - camera.lookat[1]);
    camera.lookat[2] = lookat_z;
  }

  void render(const mjData* sim_data, const VideoOptions& o, const std::string& state, std::vector<unsigned char>& rgb) {
    mju_copy(data->qpos, sim_data->qpos, model->nq);
    data->time = sim_data->time;
    mj_kinematics(model, data);
    mj_camlight(model, data);
    place_camera(o.fps);
    mjv_updateScene(model, data, &option, nullptr, &camera, mjCAT_ALL, &scene);
    const mjrRect viewport{0, 0, o.width, o.height};
    mjr_render(viewport, &scene, &context_mj);
    // Simulated time and the controller's state, top left (MuJoCo's overlay: text on a dark box).
    char values[96];
    std::snprintf(values, sizeof(values), "%.2f s\n%s", sim_data->time, state.empty() ? "-" : state.c_str());
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, "time\nstate", values, &context_mj);
    mjr_readPixels(bottom_up.data(), nullptr, viewport, &context_mj);
    // OpenGL's rows run bottom to top; video rows top to bottom.
    const std::size_t row = static_cast<std::size_t>(3 * o.width);
    rgb.resize(bottom_up.size());
    for (int y = 0; y < o.height; ++y) {
      std::memcpy(rgb.data() + y * row, bottom_up.data() + (o.height - 1 - y) * row, row);
    }
  }
};

void parse_video_size(const std::string& text, VideoOptions& options) {
  int w = 0, h = 0;
  char x = 0, rest = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &rest) != 3 || x != 'x') {
    throw InputError("--video-size '" + text + "': expected WIDTHxHEIGHT, e.g. 640x480");
  }
  options.width = w;
  options.height = h;
}

void check_video_options(const VideoOptions& o) {
  const fs::path path(o.path);
  if (path.extension() != ".mp4" || path.stem().empty()) {
    throw InputError("--video '" + o.path + "': the file name must end in .mp4");
  }
  if (o.width < 16 || o.height < 16 || o.width > 4096 || o.height > 4096 || o.width % 2 || o.height % 2) {
    throw InputError("--video-size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                     ": width and height must be even, from 16 to 4096 pixels");
  }
  if (!(o.fps >= 1.0 && o.fps <= 240.0)) {
    throw InputError("--video-fps " + std::to_string(o.fps) + ": must be from 1 to 240 frames per second");
  }
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw InputError("--video '" + o.path + "': cannot create the folder " + dir.string());
  }
  // Creating the file ffmpeg will write is the only test that also holds for root.
  const fs::path probe = dir / ("." + path.filename().string() + ".tmp");
  if (!std::ofstream(probe)) {
    throw InputError("--video '" + o.path + "': the folder " + dir.string() + " is not writable");
  }
  fs::remove(probe, ec);
}

VideoRecorder::VideoRecorder(const Simulation& sim, const VideoOptions& options) : options_(options) {
  const std::string encoders = ffmpeg_encoders();
  if (encoders.empty()) throw VideoError("--video: cannot run ffmpeg (install Debian's ffmpeg package)");
  codec_ = encoders.find(" libx264 ") != std::string::npos ? "libx264" : "mpeg4";
  gl_ = std::make_unique<Gl>(sim.plant().mj(), options_);

  const fs::path path(options_.path);
  temp_path_ = (path.parent_path() / ("." + path.filename().string() + ".tmp")).string();
  char size[32], rate[32];
  std::snprintf(size, sizeof(size), "%dx%d", options_.width, options_.height);
  std::snprintf(rate, sizeof(rate), "%.9g", options_.fps);
  std::vector<std::string> args = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-nostats", "-y",
                                   "-f", "rawvideo", "-pix_fmt", "rgb24", "-s", size, "-r", rate, "-i", "-",
                                   "-an", "-c:v", codec_};
  if (codec_ == "libx264") {
    args.insert(args.end(), {"-preset", "veryfast", "-crf", "23"});
  } else {
    args.insert(args.end(), {"-q:v", "4"});
  }
  args.insert(args.end(), {"-pix_fmt", "yuv420p", "-f", "mp4", temp_path_});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw VideoError(std::string("--video: pipe: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  const int rc = posix_spawnp(&encoder_pid_, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[0]);
  if (rc != 0) {
    close(fds[1]);
    encoder_pid_ = -1;
    throw VideoError(std::string("--video: cannot start ffmpeg: ") + std::strerror(rc));
  }
  pipe_fd_ = fds[1];
}

VideoRecorder::~VideoRecorder() {
  if (!committed_) {
    if (encoder_pid_ > 0) kill(encoder_pid_, SIGTERM);
    stop_encoder();
    std::error_code ec;
    fs::remove(temp_path_, ec);
  }
}

void VideoRecorder::cycle_start(const Simulation& sim) {
  while (sim.time() + 1e-9 >= frames_ / options_.fps) {
    render(sim, frame_);
    write_frame();
  }
}

void VideoRecorder::render(const Simulation& sim, std::vector<unsigned char>& rgb) {
  const auto start = std::chrono::steady_clock::now();
  gl_->render(sim.data(), options_, state_, rgb);
  render_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void VideoRecorder::write_frame() {
  // A dead ffmpeg must surface as an error here, not as SIGPIPE ending the process.
  struct sigaction ignore {}, previous {};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &ignore, &previous);
  const unsigned char* p = frame_.data();
  std::size_t left = frame_.size();
  int error = 0;
  while (left > 0) {
    const ssize_t n = write(pipe_fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = errno;
      break;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  sigaction(SIGPIPE, &previous, nullptr);
  if (left > 0) throw VideoError(std::string("--video: ffmpeg stopped taking frames: ") + std::strerror(error));
  ++frames_;
}

int VideoRecorder::stop_encoder() {
  if (pipe_fd_ >= 0) close(pipe_fd_);
  pipe_fd_ = -1;
  int status = 0;
  if (encoder_pid_ > 0) {
    while (waitpid(encoder_pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  encoder_pid_ = -1;
  return status;
}

void VideoRecorder::commit() {
  const int status = stop_encoder();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw VideoError("--video: ffmpeg failed writing " + temp_path_);
  }
  fs::rename(temp_path_, options_.path);
  committed_ = true;
}

}  // namespace biped
