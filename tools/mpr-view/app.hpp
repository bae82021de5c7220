#pragma once
// mpr-view's window: an SDL2 window with a streaming RGB texture, the event loop (keys, mouse,
// wheel, window close, SIGINT through SDL's quit event) and the --script runner, which pushes
// the same SDL events a user would cause. Rendering happens on the RenderThread; this loop only
// composes the latest frame with the HUD and uploads it.

#include "click_focus.hpp"
#include "command_line.hpp"
#include "controls.hpp"
#include "overlay.hpp"
#include "render_thread.hpp"
#include "script.hpp"
#include "view_options.hpp"

#include <mpr/io/image_io.hpp>

#include <SDL.h>

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

/// Opens the window on `job` (already loaded and preflighted as `l`) and runs until the window
/// is closed, Esc or Q is pressed, SIGINT arrives, or the script ends. Returns the exit status.
template <std::floating_point T>
int run_window(const mpr_cli::Job& job, const mpr_cli::Loaded<T>& l, const ViewerSettings& settings,
               const std::vector<ScriptCommand>& script) {
  using Clock = std::chrono::steady_clock;
  const std::pair<int, int> view_size = mpr_cli::view_size(job, l); // not a structured binding: Clang 14
  const int view_w = view_size.first, view_h = view_size.second;    // captures none
  const int W = view_w * job.cols, H = view_h * job.rows;
  const detail::SdlSession sdl;
  const Uint32 frame_event = SDL_RegisterEvents(1);
  const std::unique_ptr<SDL_Window, detail::SdlDeleter> window(
      SDL_CreateWindow("mpr-view", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, W, H, SDL_WINDOW_SHOWN));
  if (!window) throw std::runtime_error(std::string("cannot open a window: ") + SDL_GetError());
  std::unique_ptr<SDL_Renderer, detail::SdlDeleter> renderer(SDL_CreateRenderer(window.get(), -1, 0));
  if (!renderer) renderer.reset(SDL_CreateRenderer(window.get(), -1, SDL_RENDERER_SOFTWARE));
  if (!renderer) throw std::runtime_error(std::string("cannot draw in the window: ") + SDL_GetError());
  const std::unique_ptr<SDL_Texture, detail::SdlDeleter> texture(
      SDL_CreateTexture(renderer.get(), SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING, W, H));
  if (!texture) throw std::runtime_error(std::string("cannot create the window's texture: ") + SDL_GetError());
  const Uint32 window_id = SDL_GetWindowID(window.get());

  ViewState state;
  state.job = job;
  const ViewState initial = state;
  ViewContext ctx = make_context(job, l, view_w, view_h);
  RenderThread<T> render_thread(l, [frame_event] {
    SDL_Event e{};
    e.type = frame_event;
    SDL_PushEvent(&e);
  });

  std::uint64_t generation = 0;
  const auto submit = [&] {
    RenderRequest r;
    r.job = state.job;
    r.params = mpr_cli::frame_params(state.job, l.default_focal_depth, state.time());
    r.view_width = W / state.job.cols;
    r.view_height = H / state.job.rows;
    r.generation = ++generation;
    r.submitted = Clock::now();
    render_thread.submit(std::move(r));
  };

  mpr::Image<mpr::Rgb8> screen(W, H), picture;
  RenderedFrame shown; // the latest frame's metadata (its image moves to `picture`)
  shown.error = "rendering...";
  bool dirty = true, running = true, pending_save = false;
  bool dragging = false, drag_moved = false;
  Button drag_button = Button::left;
  int last_x = 0, last_y = 0;
  std::size_t next_command = 0;
  bool waiting = false;
  Clock::time_point wait_until{}, screenshot_since{};
  bool screenshot_waiting = false;

  const auto save = [&] {
    const std::filesystem::path png = next_save_path(job.output);
    mpr_cli::create_output_folder(png, "--output");
    mpr::write_png(png, picture);
    const std::string command = render_command(state.job, state.time(), W / state.job.cols, H / state.job.rows, png);
    std::filesystem::path txt = png;
    txt.replace_extension(".txt");
    std::ofstream out(txt);
    out << command << "\n";
    out.close();
    if (!out) throw mpr::io_error(txt.string(), "write failed");
    std::printf("saved %s and %s:\n%s\n", png.string().c_str(), txt.string().c_str(), command.c_str());
    std::fflush(stdout);
  };
  // A click prints the ray under the cursor and, on scenes, the depth of the first surface it
  // hits (a BVH built on the first click); on a --raster array and on a light field with depth
  // maps it also sets the focal depth to the depth under the cursor (click-to-focus,
  // click_focus.hpp: mpr-render's --focus-at).
  std::optional<mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast, mpr::HitDepth>> depth;
  const auto click = [&](int x, int y) -> std::optional<double> {
    const int vw = W / state.job.cols, vh = H / state.job.rows;
    const std::size_t k = static_cast<std::size_t>((y / vh) * state.job.cols + x / vw);
    const mpr_cli::FrameParams p = mpr_cli::frame_params(state.job, l.default_focal_depth, state.time());
    std::optional<double> focus;
    try {
      const mpr_cli::CameraVariant<T> camera = mpr_cli::make_camera(state.job, l, p, k, vw, vh);
      const mpr::Ray<T> ray = std::visit(
          [&](const auto& cam) {
            const mpr::Region region(0, 0, vw, vh);
            const mpr::Pixel px{x % vw, y % vh};
            const mpr::Vec2<T> uv = region.pixel_to_uv<T>(px);
            return cam.selector.ray_at(px, uv, cam.surface.point_at(uv));
          },
          camera);
      std::printf("pixel %d,%d: ray from %g,%g,%g along %g,%g,%g", x, y, double(ray.origin.x()), double(ray.origin.y()),
                  double(ray.origin.z()), double(ray.direction.x()), double(ray.direction.y()),
                  double(ray.direction.z()));
      if (l.scene) {
        if (!depth) depth.emplace(l.scene);
        const double t = static_cast<double>(depth->sample(ray));
        if (std::isfinite(t) && t > 0) {
          std::printf(", first hit at ray parameter %g", t);
        } else {
          std::printf(", no hit");
        }
      }
      std::printf("\n");
      std::fflush(stdout);
      focus = click_focus(state.job, l, x, y, std::cout);
      std::cout.flush();
    } catch (const std::exception& e) {
      std::printf("pixel %d,%d: no ray (%s)\n", x, y, e.what());
    }
    std::fflush(stdout);
    return focus;
  };

  submit();
  while (running) {
    bool changed = false;
    const auto act = [&](Action a) {
      switch (a) {
      case Action::none:
        break;
      case Action::redraw:
        dirty = true;
        break;
      case Action::changed:
        changed = true;
        dirty = true;
        break;
      case Action::save:
        pending_save = true;
        break;
      case Action::quit:
        running = false;
        break;
      }
    };
    SDL_Event e;
    bool have_event = SDL_WaitEventTimeout(&e, script.empty() ? 100 : 5) != 0;
    while (have_event) {
      if (e.type == SDL_QUIT) {
        running = false;
      } else if (e.type == SDL_WINDOWEVENT) {
        if (e.window.event == SDL_WINDOWEVENT_CLOSE) running = false;
        if (e.window.event == SDL_WINDOWEVENT_EXPOSED) dirty = true;
      } else if (e.type == SDL_KEYDOWN) {
        const std::string name = SDL_GetKeyName(e.key.keysym.sym);
        if (name == "0") { // reset to the command line's view
          const bool help = state.help;
          state = initial;
          state.help = help;
          ctx = make_context(job, l, view_w, view_h);
          act(Action::changed);
        } else {
          act(on_key(state, ctx, name));
        }
      } else if (e.type == SDL_MOUSEBUTTONDOWN) {
        dragging = true;
        drag_moved = false;
        drag_button = e.button.button == SDL_BUTTON_RIGHT    ? Button::right
                      : e.button.button == SDL_BUTTON_MIDDLE ? Button::middle
                                                             : Button::left;
        last_x = e.button.x;
        last_y = e.button.y;
      } else if (e.type == SDL_MOUSEMOTION && dragging) {
        const int dx = e.motion.x - last_x, dy = e.motion.y - last_y;
        if (dx != 0 || dy != 0) drag_moved = true;
        act(on_drag(state, ctx, drag_button, dx, dy, W, H));
        last_x = e.motion.x;
        last_y = e.motion.y;
      } else if (e.type == SDL_MOUSEBUTTONUP && dragging) {
        dragging = false;
        if (!drag_moved && e.button.x >= 0 && e.button.y >= 0 && e.button.x < W && e.button.y < H)
          if (const std::optional<double> focus = click(e.button.x, e.button.y)) {
            state.job.focal_depth = mpr_cli::Track(*focus);
            act(Action::changed);
          }
      } else if (e.type == SDL_MOUSEWHEEL) {
        const int notches = e.wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -e.wheel.y : e.wheel.y;
        act(on_wheel(state, ctx, notches, (SDL_GetModState() & KMOD_SHIFT) != 0));
      } else if (e.type == frame_event) {
        if (std::optional<RenderedFrame> f = render_thread.take(); f && f->generation >= shown.generation) {
          if (f->error.empty()) picture = std::move(f->image);
          f->image = mpr::Image<mpr::Rgb8>();
          if (ctx.raster && !state.job.focal_depth && f->error.empty()) ctx.focal_depth = f->focal_depth;
          shown = std::move(*f);
          dirty = true;
        }
      }
      have_event = SDL_PollEvent(&e) != 0;
    }
    if (!running) break;
    if (changed) submit();
    if (dirty) {
      const bool error = !shown.error.empty();
      compose(screen.view(), picture.view(), hud_text(state, ctx, shown), error, state.help);
      SDL_UpdateTexture(texture.get(), nullptr, screen.data(), W * 3);
      SDL_RenderClear(renderer.get());
      SDL_RenderCopy(renderer.get(), texture.get(), nullptr, nullptr);
      SDL_RenderPresent(renderer.get());
      dirty = false;
    }
    const bool settled = shown.generation == generation && (shown.full || !shown.error.empty());
    if (pending_save && settled) {
      if (shown.error.empty()) {
        try {
          save();
        } catch (const std::exception& e) { // the window stays open
          std::fprintf(stderr, "mpr-view: not saved: %s\n", e.what());
        }
      } else
        std::printf("not saved: %s\n", shown.error.c_str());
      pending_save = false;
    }
    // The script: input commands push events and yield to the loop, so that they are handled
    // (and the view re-requested) before the next command runs.
    const Clock::time_point now = Clock::now();
    while (next_command < script.size()) {
      const ScriptCommand& c = script[next_command];
      if (c.kind == ScriptCommand::Kind::wait) {
        if (!waiting) {
          waiting = true;
          wait_until = now + std::chrono::milliseconds(c.milliseconds);
        }
        if (now < wait_until) break;
        waiting = false;
        ++next_command;
        continue;
      }
      if (c.kind == ScriptCommand::Kind::screenshot) {
        if (!settled || SDL_PeepEvents(nullptr, 0, SDL_PEEKEVENT, SDL_FIRSTEVENT, SDL_LASTEVENT) > 0) {
          if (!screenshot_waiting) screenshot_since = now;
          screenshot_waiting = true;
          if (now - screenshot_since > std::chrono::seconds(120)) {
            std::fprintf(stderr, "mpr-view: %s:%d: screenshot: no finished frame after 120 s\n",
                         settings.script->string().c_str(), c.line);
            return 1;
          }
          break;
        }
        screenshot_waiting = false;
        mpr_cli::create_output_folder(c.path, "screenshot");
        mpr::write_png(c.path, screen);
        std::printf("screenshot %s: HUD '%s'\n", c.path.string().c_str(), hud_text(state, ctx, shown).c_str());
        std::fflush(stdout);
        ++next_command;
        continue;
      }
      detail::push_script_events(c, window_id);
      ++next_command;
      break;
    }
    if (!script.empty() && next_command == script.size() && !pending_save &&
        SDL_PeepEvents(nullptr, 0, SDL_PEEKEVENT, SDL_FIRSTEVENT, SDL_LASTEVENT) == 0)
      running = false;
  }
  return 0;
}

} // namespace mpr_view
