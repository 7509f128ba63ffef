// ddish reference SCENE --spp N --out DIR [--display single|stereo|PROFILE] [options]
//
// Converged path-traced images of the views of a frame (trace/reference.h): the ground truth
// every other figure is measured against. The views are built exactly as `ddish render` builds
// them (view_options.h: same camera, same focal distance rule, same profile overrides) and
// written by the same FrameWriter (frame_outputs.h), so an image and its reference share names:
// for one view DIR/reference.exr (linear) and DIR/reference.png (display: clamped,
// sRGB-encoded, no tone curve); for a light-field or grid display the quilt
// NAME_qs{cols}x{rows}a{aspect}.exr/.png, for stereo the side-by-side pair, and in both cases
// every view as DIR/view_NN.exr/.png. DIR/reference.json says how it was made. --time-limit
// applies to each view. With --convergence (one view only) the error of the image after 1, 4,
// 16, ... spp against the final image. --time poses the scene (node animation, skins, morph
// targets) at that time, as `ddish render --time` does for its frame 0.
//
// Reading the convergence CSV: the image after N spp holds the first N of the final image's M
// samples per pixel, so the two are correlated and the measured MSE is sigma^2 (1/N - 1/M)
// rather than the sigma^2 / N it would be against the exact image. The curve is therefore exact
// in shape but drops to 0 at N = M; points with N <= M / 16 read at most 3.2 % low (sqrt(1 - N/M)).
// Columns: spp, seconds (render time up to that pass), rmse, relmse (linear), psnr (dB), ssim
// (display).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "app/camera_options.h"
#include "app/commands.h"
#include "app/frame_outputs.h"
#include "app/lighting_options.h"
#include "app/view_options.h"
#include "io/atomic_file.h"
#include "metrics/errors.h"
#include "metrics/image.h"
#include "metrics/image_io.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "scene/view.h"
#include "trace/reference.h"
#include "trace/tracer.h"

namespace ddish::app {
namespace {

namespace fs = std::filesystem;

struct ReferenceArgs {
  std::string scene;
  CameraArgs view;  // --camera, --fov, --width, --height (shared with `ddish render`)
  DisplayArgs display;  // --display, --views, --focal-distance (shared with `ddish render`)
  LightingArgs lighting;  // --sky, --exposure (shared with `ddish render`)
  int spp = 256;
  double time_limit = 0.0;
  double time = 0.0;  // scene time (seconds) the scene is posed at
  std::uint64_t seed = 1;
  int bounces = 16;
  std::string out;
  std::string convergence;
};

metrics::Image to_image(const trace::ReferenceImage& r) {
  metrics::Image img(r.width, r.height);
  img.pixels() = r.pixels;
  return img;
}

// A progress bar with ETA on stderr when it is a terminal; one line per finished pass otherwise
// (logs stay readable).
class ProgressBar {
 public:
  ProgressBar() : tty_(::isatty(STDERR_FILENO) != 0) {}

  void update(const trace::ReferenceProgress& p) {
    if (!tty_) return;
    constexpr int kWidth = 30;
    int filled = static_cast<int>(p.fraction * kWidth);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    std::string eta = p.fraction > 0.0 && p.fraction < 1.0
                          ? fmt::format("ETA {:.1f} s", p.elapsed_s * (1.0 / p.fraction - 1.0))
                          : "";
    std::fprintf(stderr, "\r[%s] %5.1f%%  %.1f s  %d/%d spp  %-16s", bar.c_str(),
                 100.0 * p.fraction, p.elapsed_s, p.spp_done, p.spp_target, eta.c_str());
    if (p.fraction >= 1.0) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

  void pass(int spp, double seconds) {
    if (tty_) return;
    std::fprintf(stderr, "reference: %d spp after %.2f s\n", spp, seconds);
  }

 private:
  bool tty_;
};

struct ConvergencePoint {
  int spp;
  double seconds;
  metrics::Image image;
};

bool is_power_of_four(int n) {
  while (n > 1 && n % 4 == 0) n /= 4;
  return n == 1;
}

void write_convergence(const fs::path& path, const std::vector<ConvergencePoint>& points,
                       const metrics::Image& final_image) {
  std::ostringstream csv;
  csv << "spp,seconds,rmse,relmse,psnr,ssim\n";
  for (const ConvergencePoint& p : points) {
    metrics::ImageErrors e = metrics::compute_errors(p.image, final_image);
    csv << p.spp << ',' << fmt::format("{:.4f}", p.seconds) << ','
        << metrics::format_figure(e.rmse, 8) << ',' << metrics::format_figure(e.relmse, 8) << ','
        << metrics::format_figure(e.psnr, 8) << ',' << metrics::format_figure(e.ssim, 8) << '\n';
  }
  io::write_file_atomically(path, csv.str());
}

nlohmann::ordered_json view_meta(const scene::View& view, const trace::ReferenceImage& r) {
  nlohmann::ordered_json v;
  v["view"] = view.name;
  v["spp"] = r.spp;
  v["time_limited"] = r.time_limited;
  v["seconds"] = r.seconds;
  v["rays"] = r.rays;
  v["nonfinite_samples"] = r.nonfinite_samples;
  v["invalid_paths"] = r.invalid_paths;
  return v;
}

int run_reference(const ReferenceArgs& args) {
  parse_pose(args.view.camera);  // a malformed --camera fails before the (possibly slow) load
  sky_radiance(args.lighting);
  const DisplayChoice choice = resolve_display(args.display, args.view);
  if (!choice.single() && !args.convergence.empty())
    throw std::invalid_argument("--convergence measures one view; it cannot be used with --display " +
                                args.display.display);
  // Fail before a long load and render, not after them, when the outputs cannot be written.
  const fs::path out_dir(args.out);
  io::check_writable_folder(out_dir);
  if (!args.convergence.empty()) io::check_writable_file(args.convergence);
  scene::Scene s = scene::load_scene(args.scene);
  s.pose(args.time);
  const std::string framing = frame_camera_less(s, args.view, view_aspect(choice, args.view));
  const std::string environment = apply_lighting(s, args.lighting);
  const display::ViewSet set = make_frame_views(s, choice, args.display, args.view);
  // Said once the views and outputs are known to be good: bad input gets its one error line only.
  if (!framing.empty()) std::fprintf(stderr, "reference: %s\n", framing.c_str());
  std::fprintf(stderr, "reference: %s\n", environment.c_str());

  trace::PathOptions path_options;
  path_options.max_bounces = args.bounces;
  const trace::Tracer tracer(s, path_options);

  trace::ReferenceOptions options;
  options.spp = args.spp;
  options.time_limit_s = args.time_limit;
  options.seed = args.seed;

  ProgressBar bar;
  std::vector<ConvergencePoint> points;
  trace::ReferenceCallbacks callbacks;
  callbacks.progress = [&bar](const trace::ReferenceProgress& p) { bar.update(p); };
  callbacks.pass_done = [&](const trace::ReferenceImage& img) {
    bar.pass(img.spp, img.seconds);
    // The final image is the convergence curve's reference, so its own point is not kept.
    if (!args.convergence.empty() && is_power_of_four(img.spp) && img.spp < args.spp)
      points.push_back({img.spp, img.seconds, to_image(img)});
  };

  std::vector<metrics::Image> images;  // linear, one per view
  nlohmann::ordered_json per_view = nlohmann::ordered_json::array();
  trace::ReferenceImage totals;  // summed over the views; spp is the least any view reached
  totals.spp = args.spp;
  for (std::size_t i = 0; i < set.size(); ++i) {
    if (set.size() > 1) std::fprintf(stderr, "reference: view %zu/%zu\n", i + 1, set.size());
    const trace::ReferenceImage r = trace::render_reference(tracer, set.views[i], options, callbacks);
    images.push_back(to_image(r));
    per_view.push_back(view_meta(set.views[i], r));
    totals.spp = std::min(totals.spp, r.spp);
    totals.time_limited = totals.time_limited || r.time_limited;
    totals.seconds += r.seconds;
    totals.rays += r.rays;
    totals.nonfinite_samples += r.nonfinite_samples;
    totals.invalid_paths += r.invalid_paths;
  }
  // The reference has no tone curve: its PNG is the linear image (times --exposure's 2^EV)
  // clamped and sRGB-encoded.
  const float exposure = exposure_scale(args.lighting);
  const FrameWriter writer(set, {.dir = out_dir,
                                 .stem = fs::path(args.scene).stem().string(),
                                 .per_view = !choice.single(),
                                 .calibration = std::nullopt});
  const std::vector<fs::path> written = writer.write(LinearFrameViews(images, exposure), "reference", "");
  if (!args.convergence.empty()) {
    // A time-limited run ends below --spp: drop the points at or above what it reached.
    std::erase_if(points, [&](const ConvergencePoint& p) { return p.spp >= totals.spp; });
    write_convergence(args.convergence, points, images.front());
  }

  const scene::View& view = set.views.front();
  const double mrays = totals.seconds > 0.0 ? double(totals.rays) / totals.seconds * 1e-6 : 0.0;
  nlohmann::ordered_json meta;
  meta["scene"] = args.scene;
  meta["display"] = set.name;
  meta["view"] = view.name;
  meta["views"] = set.size();
  meta["width"] = view.width;
  meta["height"] = view.height;
  meta["spp"] = totals.spp;
  meta["spp_requested"] = args.spp;
  meta["time_limited"] = totals.time_limited;
  meta["seed"] = args.seed;
  meta["time"] = args.time;
  meta["bounces"] = args.bounces;
  meta["seconds"] = totals.seconds;
  meta["rays"] = totals.rays;
  meta["mrays_per_s"] = mrays;
  meta["nonfinite_samples"] = totals.nonfinite_samples;
  meta["invalid_paths"] = totals.invalid_paths;
  if (set.size() > 1) meta["per_view"] = per_view;
  io::write_file_atomically(out_dir / "reference.json", meta.dump(2) + '\n');

  std::printf("reference: %zu view%s of %dx%d, %d spp%s in %.2f s, %.2f Mrays/s (%llu rays)\n",
              set.size(), set.size() == 1 ? "" : "s", view.width, view.height, totals.spp,
              totals.time_limited ? " (time limit)" : "", totals.seconds, mrays,
              static_cast<unsigned long long>(totals.rays));
  if (totals.nonfinite_samples > 0 || totals.invalid_paths > 0)
    std::printf("reference: %llu NaN/Inf samples dropped, %llu invalid paths zeroed by the tracer\n",
                static_cast<unsigned long long>(totals.nonfinite_samples),
                static_cast<unsigned long long>(totals.invalid_paths));
  for (const fs::path& p : written) std::printf("wrote %s\n", p.string().c_str());
  if (!args.convergence.empty()) std::printf("wrote %s\n", args.convergence.c_str());
  return 0;
}

Action add_reference(CLI::App& root) {
  auto args = std::make_shared<ReferenceArgs>();
  CLI::App* cmd = root.add_subcommand(
      "reference", "converged path-traced images (ground truth) of the views of a display");
  cmd->add_option("scene", args->scene, "glTF scene (.gltf or .glb)")
      ->required()
      ->check(CLI::ExistingFile);
  add_camera_options(*cmd, args->view);
  add_display_options(*cmd, args->display);
  add_lighting_options(*cmd, args->lighting, /*exposure=*/true);
  cmd->add_option("--spp", args->spp, "samples per pixel")
      ->capture_default_str()
      ->check(CLI::Range(1, 1 << 24));
  cmd->add_option("--time-limit", args->time_limit,
                  "seconds: stop after the last progressive pass (1, 2, 4, ... spp) that fits")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            double v = -1.0;
            try {
              v = std::stod(text);
            } catch (const std::exception&) {
            }
            return v >= 0.0 && std::isfinite(v) ? "" : "'" + text + "' is not a number of seconds >= 0";
          },
          "SECONDS"));
  cmd->add_option("--seed", args->seed, "random seed")->capture_default_str();
  cmd->add_option("--time", args->time, "scene time the scene is posed at (seconds), as render's --time")
      ->capture_default_str();
  cmd->add_option("--bounces", args->bounces, 
                  "scattering events per camera path, the camera ray's hit counting as one: 0 only "
                  "emitters and sky seen directly, 1 direct light only, 2 one indirect bounce, ...")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--out", args->out, "output directory")->required();
  cmd->add_option("--convergence", args->convergence,
                  "CSV of the error after 1, 4, 16, ... spp against the final image");
  return [args] { return run_reference(*args); };
}

}  // namespace

DDISH_COMMAND(40, add_reference);

}  // namespace ddish::app
