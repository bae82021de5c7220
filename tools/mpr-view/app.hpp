#pragma once
// mpr-view's window: a resizable SDL2 window with a streaming RGB texture of its size, the event
// loop (keys, mouse, wheel, resize, window close, SIGINT through SDL's quit event) and the
// --script runner, which pushes the same SDL events a user would cause. Rendering happens on the RenderThread; this
// loop only composes the latest frame with the HUD and uploads it.

#include "click_focus.hpp"
#include "command_line.hpp"
#include "controls.hpp"
#include "overlay.hpp"
#include "render_thread.hpp"
#include "script.hpp"
#include "view_options.hpp"

#include <mpr/io/image_io.hpp>

#include <SDL.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace mpr_view {

/// The context of the controls for a loaded job with views of `view_width` x `view_height`.
template <std::floating_point T>
ViewContext make_context(const mpr_cli::Job& job, const mpr_cli::Loaded<T>& l, int view_width, int view_height) {
  ViewContext ctx;
  ctx.light_field = mpr_cli::is_light_field(job.sampler);
  ctx.raster = job.raster.has_value();
  ctx.plane_centre = job.plane_centre ? *job.plane_centre : l.plane_centre;
  ctx.look_at = job.look_at ? *job.look_at : l.look_at;
  ctx.plane_width = job.plane_size ? job.plane_size->first : l.plane_width;
  ctx.plane_height = job.plane_size ? job.plane_size->second : ctx.plane_width * view_height / view_width;
  ctx.focal_depth = l.default_focal_depth;
  // What mpr-render would choose for a gallery letter on this array (with_array_defaults): the
  // letter keys apply it when the user gave no interpolation or radius.
  if (ctx.light_field || ctx.raster) {
    mpr_cli::Job lettered = job;
    lettered.views = {"A"};
    const mpr_cli::Job chosen = mpr_cli::with_array_defaults(lettered, l);
    ctx.letter_interpolation = chosen.interpolation;
    ctx.letter_radius = chosen.radius;
  }
  return ctx;
}

/// The first free "<stem>_NNNN.png" next to `base`.
inline std::filesystem::path next_save_path(const std::filesystem::path& base) {
  for (int n = 1;; ++n) {
    char number[16];
    std::snprintf(number, sizeof number, "_%04d.png", n);
    std::filesystem::path p = base;
    p.replace_filename(base.stem().string() + number);
    std::error_code ec;
    if (!std::filesystem::exists(p, ec) || n == 9999) return p;
  }
}

namespace detail {

struct SdlDeleter {
  void operator()(SDL_Window* w) const noexcept { SDL_DestroyWindow(w); }
  void operator()(SDL_Renderer* r) const noexcept { SDL_DestroyRenderer(r); }
  void operator()(SDL_Texture* t) const noexcept { SDL_DestroyTexture(t); }
};

/// SDL_Init / SDL_Quit.
struct SdlSession {
  SdlSession() {
    if (SDL_Init(SDL_INIT_VIDEO) != 0) throw std::runtime_error(std::string("cannot open a window: ") + SDL_GetError());
  }
  ~SdlSession() { SDL_Quit(); }
  SdlSession(const SdlSession&) = delete;
  SdlSession& operator=(const SdlSession&) = delete;
};

inline void push_button(Uint32 window, Uint32 type, Uint8 button, int x, int y) {
  SDL_Event e{};
  e.type = type;
  e.button.windowID = window;
  e.button.button = button;
  e.button.state = type == SDL_MOUSEBUTTONDOWN ? SDL_PRESSED : SDL_RELEASED;
  e.button.clicks = 1;
  e.button.x = x;
  e.button.y = y;
  SDL_PushEvent(&e);
}

inline void push_motion(Uint32 window, int x, int y, int dx, int dy) {
  SDL_Event e{};
  e.type = SDL_MOUSEMOTION;
  e.motion.windowID = window;
  e.motion.x = x;
  e.motion.y = y;
  e.motion.xrel = dx;
  e.motion.yrel = dy;
  SDL_PushEvent(&e);
}

/// Pushes the SDL events of one script input command.
inline void push_script_events(const ScriptCommand& c, Uint32 window) {
  switch (c.kind) {
  case ScriptCommand::Kind::key:
    for (const Uint32 type : {Uint32(SDL_KEYDOWN), Uint32(SDL_KEYUP)}) {
      SDL_Event e{};
      e.type = type;
      e.key.windowID = window;
      e.key.state = type == SDL_KEYDOWN ? SDL_PRESSED : SDL_RELEASED;
      e.key.keysym.sym = SDL_GetKeyFromName(c.key.c_str());
      e.key.keysym.scancode = SDL_GetScancodeFromKey(e.key.keysym.sym);
      SDL_PushEvent(&e);
    }
    break;
  case ScriptCommand::Kind::drag: {
    const Uint8 button = c.button == "right"    ? SDL_BUTTON_RIGHT
                         : c.button == "middle" ? SDL_BUTTON_MIDDLE
                                                : SDL_BUTTON_LEFT;
    push_button(window, SDL_MOUSEBUTTONDOWN, button, c.x0, c.y0);
    constexpr int steps = 8;
    int x = c.x0, y = c.y0;
    for (int i = 1; i <= steps; ++i) {
      const int nx = c.x0 + (c.x1 - c.x0) * i / steps, ny = c.y0 + (c.y1 - c.y0) * i / steps;
      push_motion(window, nx, ny, nx - x, ny - y);
      x = nx;
      y = ny;
    }
    push_button(window, SDL_MOUSEBUTTONUP, button, c.x1, c.y1);
    break;
  }
  case ScriptCommand::Kind::wheel: {
    SDL_Event e{};
    e.type = SDL_MOUSEWHEEL;
    e.wheel.windowID = window;
    e.wheel.y = c.notches;
    e.wheel.direction = SDL_MOUSEWHEEL_NORMAL;
    SDL_PushEvent(&e);
    break;
  }
  case ScriptCommand::Kind::click:
    push_button(window, SDL_MOUSEBUTTONDOWN, SDL_BUTTON_LEFT, c.x0, c.y0);
    push_button(window, SDL_MOUSEBUTTONUP, SDL_BUTTON_LEFT, c.x0, c.y0);
    break;
  default:
    break;
  }
}

} // namespace detail

/// The interactive window on a loaded job: owns the SDL window, its texture, the render thread
/// and the view state; `run` is the event loop (see run_window).
template <std::floating_point T>
class ViewerWindow {
public:
  using Clock = std::chrono::steady_clock;

  ViewerWindow(const mpr_cli::Job& job, const mpr_cli::Loaded<T>& l, const ViewerSettings& settings,
               const std::vector<ScriptCommand>& script)
      : job_(job), l_(l), settings_(settings), script_(script), render_thread_(l, [this] {
          SDL_Event e{};
          e.type = frame_event_;
          SDL_PushEvent(&e);
        }) {
    const std::pair<int, int> view = mpr_cli::view_size(job, l); // not a structured binding: Clang 14
    open(view.first * job.cols, view.second * job.rows);
    state_.job = job;
    initial_ = state_;
    ctx_ = make_context(job, l, W_ / job.cols, H_ / job.rows);
    shown_.error = "rendering...";
  }

  /// Runs until the window is closed, Esc or Q is pressed, SIGINT arrives, or the script ends.
  /// Returns the exit status (1: a screenshot of the script never got its frame).
  int run() {
    submit();
    while (running_) {
      changed_ = false;
      SDL_Event e;
      bool have_event = SDL_WaitEventTimeout(&e, script_.empty() ? 100 : 5) != 0;
      while (have_event) {
        handle(e);
        have_event = SDL_PollEvent(&e) != 0;
      }
      if (!running_) break;
      if (changed_) submit();
      if (dirty_) present();
      if (pending_save_ && settled()) save_now();
      if (!step_script()) return 1;
      if (!script_.empty() && next_command_ == script_.size() && !pending_save_ && queue_empty()) running_ = false;
    }
    return 0;
  }

private:
  /// Creates the resizable window of `width` x `height` pixels and its renderer, then the
  /// texture and screen image of that size (resize).
  void open(int width, int height) {
    frame_event_ = SDL_RegisterEvents(1);
    window_.reset(SDL_CreateWindow("mpr-view", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, width, height,
                                   SDL_WINDOW_SHOWN | SDL_WINDOW_RESIZABLE));
    if (!window_) throw std::runtime_error(std::string("cannot open a window: ") + SDL_GetError());
    SDL_SetWindowMinimumSize(window_.get(), std::max(16, job_.cols), std::max(16, job_.rows));
    renderer_.reset(SDL_CreateRenderer(window_.get(), -1, 0));
    if (!renderer_) renderer_.reset(SDL_CreateRenderer(window_.get(), -1, SDL_RENDERER_SOFTWARE));
    if (!renderer_) throw std::runtime_error(std::string("cannot draw in the window: ") + SDL_GetError());
    window_id_ = SDL_GetWindowID(window_.get());
    resize(width, height);
  }

  /// The window is now `width` x `height`: the image the views fill takes that size (each view
  /// width / cols x height / rows; a scene's image plane keeps its width and takes the new
  /// aspect ratio), and the view is rendered again at it.
  void resize(int width, int height) {
    if (width == W_ && height == H_) return;
    W_ = std::max(width, state_.job.cols);
    H_ = std::max(height, state_.job.rows);
    texture_.reset(SDL_CreateTexture(renderer_.get(), SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING, W_, H_));
    if (!texture_) throw std::runtime_error(std::string("cannot create the window's texture: ") + SDL_GetError());
    screen_ = mpr::Image<mpr::Rgb8>(W_, H_);
    const double aspect = static_cast<double>(view_height()) / view_width();
    ctx_.plane_height = ctx_.plane_width * aspect;
    if (state_.job.plane_size) state_.job.plane_size->second = state_.job.plane_size->first * aspect;
    changed_ = dirty_ = true;
  }

  [[nodiscard]] int view_width() const noexcept { return W_ / state_.job.cols; }
  [[nodiscard]] int view_height() const noexcept { return H_ / state_.job.rows; }

  void submit() {
    RenderRequest r;
    r.job = state_.job;
    r.params = mpr_cli::frame_params(state_.job, l_.default_focal_depth, state_.time());
    r.view_width = view_width();
    r.view_height = view_height();
    r.generation = ++generation_;
    r.submitted = Clock::now();
    render_thread_.submit(std::move(r));
  }

  void act(Action a) {
    switch (a) {
    case Action::none:
      break;
    case Action::redraw:
      dirty_ = true;
      break;
    case Action::changed:
      changed_ = dirty_ = true;
      break;
    case Action::save:
      pending_save_ = true;
      break;
    case Action::quit:
      running_ = false;
      break;
    }
  }

  /// One SDL event: window, keys, mouse, wheel, or a finished frame.
  void handle(const SDL_Event& e) {
    if (e.type == SDL_QUIT) {
      running_ = false;
    } else if (e.type == SDL_WINDOWEVENT) {
      if (e.window.event == SDL_WINDOWEVENT_CLOSE) running_ = false;
      if (e.window.event == SDL_WINDOWEVENT_EXPOSED) dirty_ = true;
      if (e.window.event == SDL_WINDOWEVENT_SIZE_CHANGED) resize(e.window.data1, e.window.data2);
    } else if (e.type == SDL_KEYDOWN) {
      on_key_down(SDL_GetKeyName(e.key.keysym.sym));
    } else if (e.type == SDL_MOUSEBUTTONDOWN) {
      dragging_ = true;
      drag_moved_ = false;
      drag_button_ = e.button.button == SDL_BUTTON_RIGHT    ? Button::right
                     : e.button.button == SDL_BUTTON_MIDDLE ? Button::middle
                                                            : Button::left;
      last_x_ = e.button.x;
      last_y_ = e.button.y;
    } else if (e.type == SDL_MOUSEMOTION && dragging_) {
      const int dx = e.motion.x - last_x_, dy = e.motion.y - last_y_;
      if (dx != 0 || dy != 0) drag_moved_ = true;
      act(on_drag(state_, ctx_, drag_button_, dx, dy, W_, H_));
      last_x_ = e.motion.x;
      last_y_ = e.motion.y;
    } else if (e.type == SDL_MOUSEBUTTONUP && dragging_) {
      dragging_ = false;
      if (!drag_moved_ && e.button.x >= 0 && e.button.y >= 0 && e.button.x < W_ && e.button.y < H_)
        if (const std::optional<double> focus = click(e.button.x, e.button.y)) {
          state_.job.focal_depth = mpr_cli::Track(*focus);
          act(Action::changed);
        }
    } else if (e.type == SDL_MOUSEWHEEL) {
      const int notches = e.wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -e.wheel.y : e.wheel.y;
      act(on_wheel(state_, ctx_, notches, (SDL_GetModState() & KMOD_SHIFT) != 0));
    } else if (e.type == frame_event_) {
      take_frame();
    }
  }

  void on_key_down(const std::string& name) {
    if (name != "0") {
      act(on_key(state_, ctx_, name));
      return;
    }
    // Back to the command line's view (at the window's present size).
    const bool help = state_.help;
    state_ = initial_;
    state_.help = help;
    ctx_ = make_context(job_, l_, view_width(), view_height());
    if (state_.job.plane_size)
      state_.job.plane_size->second = state_.job.plane_size->first * view_height() / view_width();
    act(Action::changed);
  }

  /// The render thread's newest frame, when it is not older than the one shown.
  void take_frame() {
    std::optional<RenderedFrame> f = render_thread_.take();
    if (!f || f->generation < shown_.generation) return;
    if (f->error.empty()) picture_ = std::move(f->image);
    f->image = mpr::Image<mpr::Rgb8>();
    if (ctx_.raster && !state_.job.focal_depth && f->error.empty()) ctx_.focal_depth = f->focal_depth;
    shown_ = std::move(*f);
    dirty_ = true;
  }

  /// Composes the picture with the HUD (and help) and shows it.
  void present() {
    compose(screen_.view(), picture_.view(), hud_text(state_, ctx_, shown_), !shown_.error.empty(), state_.help);
    SDL_UpdateTexture(texture_.get(), nullptr, screen_.data(), W_ * 3);
    SDL_RenderClear(renderer_.get());
    SDL_RenderCopy(renderer_.get(), texture_.get(), nullptr, nullptr);
    SDL_RenderPresent(renderer_.get());
    dirty_ = false;
  }

  /// The view asked for last is shown at full resolution (or cannot be rendered).
  [[nodiscard]] bool settled() const noexcept {
    return shown_.generation == generation_ && (shown_.full || !shown_.error.empty());
  }
  [[nodiscard]] static bool queue_empty() noexcept {
    return SDL_PeepEvents(nullptr, 0, SDL_PEEKEVENT, SDL_FIRSTEVENT, SDL_LASTEVENT) == 0;
  }

  /// `S`, once the view is settled: the picture and the mpr-render command that renders it.
  void save_now() {
    pending_save_ = false;
    if (!shown_.error.empty()) {
      std::printf("not saved: %s\n", shown_.error.c_str());
      return;
    }
    try {
      const std::filesystem::path png = next_save_path(job_.output);
      mpr_cli::create_output_folder(png, "--output");
      mpr::write_png(png, picture_);
      const std::string command = render_command(state_.job, state_.time(), view_width(), view_height(), png);
      std::filesystem::path txt = png;
      txt.replace_extension(".txt");
      std::ofstream out(txt);
      out << command << "\n";
      out.close();
      if (!out) throw mpr::io_error(txt.string(), "write failed");
      std::printf("saved %s and %s:\n%s\n", png.string().c_str(), txt.string().c_str(), command.c_str());
      std::fflush(stdout);
    } catch (const std::exception& e) { // the window stays open
      std::fprintf(stderr, "mpr-view: not saved: %s\n", e.what());
    }
  }

  /// The ray under window pixel (x, y) of the current view.
  [[nodiscard]] mpr::Ray<T> ray_at(int x, int y) const {
    const int vw = view_width(), vh = view_height();
    const std::size_t k = static_cast<std::size_t>((y / vh) * state_.job.cols + x / vw);
    const mpr_cli::FrameParams p = mpr_cli::frame_params(state_.job, l_.default_focal_depth, state_.time());
    const mpr_cli::CameraVariant<T> camera = mpr_cli::make_camera(state_.job, l_, p, k, vw, vh);
    return std::visit(
        [&](const auto& cam) {
          const mpr::Region region(0, 0, vw, vh);
          const mpr::Pixel px{x % vw, y % vh};
          const mpr::Vec2<T> uv = region.pixel_to_uv<T>(px);
          return cam.selector.ray_at(px, uv, cam.surface.point_at(uv));
        },
        camera);
  }

  /// A click prints the ray under the cursor and, on scenes, the depth of the first surface it
  /// hits (a BVH built on the first click); on a --raster array and on a light field with depth
  /// maps it returns the depth under the cursor as the new focal depth (click-to-focus,
  /// click_focus.hpp: mpr-render's --focus-at).
  std::optional<double> click(int x, int y) {
    std::optional<double> focus;
    try {
      const mpr::Ray<T> ray = ray_at(x, y);
      std::printf("pixel %d,%d: ray from %g,%g,%g along %g,%g,%g", x, y, double(ray.origin.x()), double(ray.origin.y()),
                  double(ray.origin.z()), double(ray.direction.x()), double(ray.direction.y()),
                  double(ray.direction.z()));
      if (l_.scene) {
        if (!depth_) depth_.emplace(l_.scene);
        const double t = static_cast<double>(depth_->sample(ray));
        if (std::isfinite(t) && t > 0)
          std::printf(", first hit at ray parameter %g", t);
        else
          std::printf(", no hit");
      }
      std::printf("\n");
      std::fflush(stdout);
      focus = click_focus(state_.job, l_, x, y, std::cout);
      std::cout.flush();
    } catch (const std::exception& e) {
      std::printf("pixel %d,%d: no ray (%s)\n", x, y, e.what());
    }
    std::fflush(stdout);
    return focus;
  }

  /// Writes the window's content for a `screenshot` command once the view is settled and no
  /// event is pending. False while it must wait; throws after 120 s without a frame.
  bool screenshot(const ScriptCommand& c, Clock::time_point now) {
    if (!settled() || !queue_empty()) {
      if (!screenshot_waiting_) screenshot_since_ = now;
      screenshot_waiting_ = true;
      if (now - screenshot_since_ > std::chrono::seconds(120))
        throw std::runtime_error(settings_.script->string() + ":" + std::to_string(c.line) +
                                 ": screenshot: no finished frame after 120 s");
      return false;
    }
    screenshot_waiting_ = false;
    mpr_cli::create_output_folder(c.path, "screenshot");
    mpr::write_png(c.path, screen_);
    std::printf("screenshot %s: HUD '%s'\n", c.path.string().c_str(), hud_text(state_, ctx_, shown_).c_str());
    std::fflush(stdout);
    return true;
  }

  /// Runs the script up to its next input command, which pushes its events and yields to the
  /// loop so that they are handled (and the view requested) before the next command runs.
  /// False when a screenshot timed out (reported on stderr).
  bool step_script() {
    const Clock::time_point now = Clock::now();
    while (next_command_ < script_.size()) {
      const ScriptCommand& c = script_[next_command_];
      if (c.kind == ScriptCommand::Kind::wait) {
        if (!waiting_) {
          waiting_ = true;
          wait_until_ = now + std::chrono::milliseconds(c.milliseconds);
        }
        if (now < wait_until_) return true;
        waiting_ = false;
        ++next_command_;
        continue;
      }
      if (c.kind == ScriptCommand::Kind::screenshot) {
        try {
          if (!screenshot(c, now)) return true;
        } catch (const std::runtime_error& e) {
          std::fprintf(stderr, "mpr-view: %s\n", e.what());
          return false;
        }
        ++next_command_;
        continue;
      }
      if (c.kind == ScriptCommand::Kind::resize)
        SDL_SetWindowSize(window_.get(), c.x1, c.y1); // the window's size event follows
      else
        detail::push_script_events(c, window_id_);
      ++next_command_;
      return true;
    }
    return true;
  }

  const mpr_cli::Job& job_;
  const mpr_cli::Loaded<T>& l_;
  const ViewerSettings& settings_;
  const std::vector<ScriptCommand>& script_;
  detail::SdlSession sdl_;
  Uint32 frame_event_ = 0, window_id_ = 0;
  std::unique_ptr<SDL_Window, detail::SdlDeleter> window_;
  std::unique_ptr<SDL_Renderer, detail::SdlDeleter> renderer_;
  std::unique_ptr<SDL_Texture, detail::SdlDeleter> texture_;
  int W_ = 0, H_ = 0; ///< the window's (and the rendered image's) size in pixels
  ViewState state_, initial_;
  ViewContext ctx_;
  mpr::Image<mpr::Rgb8> screen_, picture_;
  RenderedFrame shown_; ///< the latest frame's metadata (its image moves to `picture_`)
  std::uint64_t generation_ = 0;
  bool dirty_ = true, running_ = true, changed_ = false, pending_save_ = false;
  bool dragging_ = false, drag_moved_ = false;
  Button drag_button_ = Button::left;
  int last_x_ = 0, last_y_ = 0;
  std::size_t next_command_ = 0;
  bool waiting_ = false, screenshot_waiting_ = false;
  Clock::time_point wait_until_{}, screenshot_since_{};
  std::optional<mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast, mpr::HitDepth>> depth_;
  RenderThread<T> render_thread_; // last: stopped (joined) first, before the SDL objects go
};

/// Opens the window on `job` (already loaded and preflighted as `l`) and runs until the window
/// is closed, Esc or Q is pressed, SIGINT arrives, or the script ends. Returns the exit status.
template <std::floating_point T>
int run_window(const mpr_cli::Job& job, const mpr_cli::Loaded<T>& l, const ViewerSettings& settings,
               const std::vector<ScriptCommand>& script) {
  ViewerWindow<T> window(job, l, settings, script);
  return window.run();
}

} // namespace mpr_view
