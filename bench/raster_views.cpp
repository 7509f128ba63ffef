// Raster cost of N views per frame for each way of recording them (raster/view_method.h), with
// and without cluster culling: ms per frame for a light-field rig (the Looking Glass camera
// model of src/display) around the scene's camera. Shadow maps of a static scene are drawn once
// and kept, so the timed frames are the forward passes, the tonemap and the readback. Probes are
// left empty: the per-view cost does not depend on what they hold.
//
//   raster_views [SCENE] [--views 1,6,12,48] [--size 420x560] [--frames 3] [--msaa 0] [--chunk 0]
//                [--method per-view|multiview|layered] [--cull on|off|both] [--only-view K]
//                [--per-chunk] [--shading full|trivial|both] [--anisotropy N]
//                [--prepass auto|on|off|both] [--shading-pass auto|forward|visibility|both]
//                [--probe-visibility R]
//
// --probe-visibility R gives the volume R x R distance-moment maps (0, the default: none), so the
// full shader takes the visibility-aware interpolation (shaders/include/probe_lighting.glsl); the
// moments are set to a wall at a fifth of the range with some spread, so that the Chebyshev term
// is evaluated rather than skipped.
//
// --shading trivial draws the same triangles with the same vertex shader, depth test, MSAA,
// passes and target but a constant-colour fragment shader (raster/shading.h): the vertex +
// raster + fill floor of the machine, which the full shading's time is compared against; both
// times each configuration with either shader (the CSV's shading column). --prepass is
// RendererOptions::depth_prepass for the full shading (auto: where the device has post-depth
// coverage; both: full shading with and without it, the CSV's prepass column). --shading-pass is
// RendererOptions::shading_pass for the full shading (auto: the renderer's choice; both:
// forward and visibility, the CSV's shading_pass column; the trivial floor is always one
// forward pass, raster/shading_pass.h). --anisotropy is
// RendererOptions::anisotropy (0 automatic: off on lavapipe; 8 reproduces the old default).
//
// --chunk K renders a frame of N views as render() calls of at most K views each (summed): on a
// loaded 2-core machine a 48-view lavapipe frame can outlast the 60 s fence wait of
// gpu::CommandRunner. Layered then records ceil(N / K) passes instead of one. --per-chunk prints
// each render() call's forward GPU time and first eye to stderr (with --chunk 1: per view), and
// --only-view K renders only view K of the N-view rig: together they find a view that costs far
// more than its neighbours (how the Sponza 48-view cliff was traced to anisotropic filtering).
//
// Prints one CSV row per method x culling x shading x N (configurations interleaved frame by frame): median over the frames of the whole frame
// (record + GPU + readback), the forward pass's GPU time (timestamps), the CPU recording time,
// the triangles and draw calls the culling left, and the readback's share of the frame (which
// `ddish render` pays only on the frames it writes).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "display/lightfield_rig.h"
#include "display/quilt_layout.h"
#include "display/view_set.h"
#include "gpu/context.h"
#include "gpu/device.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "raster/anisotropy.h"
#include "raster/renderer.h"
#include "raster/shading.h"
#include "raster/shading_pass.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"

namespace {

using namespace ddish;

double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::vector<int> parse_list(const std::string& text) {
  std::vector<int> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::stoi(item));
  return out;
}

std::vector<scene::View> rig(const scene::Scene& s, int views, int width, int height) {
  const scene::Camera* camera = s.default_camera();
  scene::Camera fallback;
  if (!camera) {
    fallback.eye = s.bounds().center() + glm::vec3(0, 0, 1.5f * glm::length(s.bounds().extent()));
    camera = &fallback;
  }
  const float focal = display::focal_distance_to_scene_center(s, camera->eye, camera->forward);
  display::LightFieldParams params;
  params.views = views;
  const display::QuiltLayout layout = display::layout_from_tiles(views, 1, width, height);
  return display::lightfield_rig(display::base_camera(*camera, focal), params, layout,
                                 float(width) / float(height)).views;
}

}  // namespace

int main(int argc, char** argv) try {
  std::string path = "/work/shared/scenes/breakfast_room/BreakfastRoom.gltf";
  std::vector<int> counts{1, 6, 12, 48};
  int width = 420, height = 560, frames = 3;
  std::uint32_t msaa = 0;
  int chunk = 0;
  bool per_chunk = false;
  std::string only_method;
  std::string cull_choice = "both";
  std::string shading_choice = "full";
  int anisotropy = 0;
  int only_view = -1;
  std::string prepass_choice = "auto";
  std::string pass_choice = "auto";
  int visibility = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--views") counts = parse_list(next());
    else if (a == "--size") std::sscanf(next().c_str(), "%dx%d", &width, &height);
    else if (a == "--frames") frames = std::stoi(next());
    else if (a == "--chunk") chunk = std::stoi(next());
    else if (a == "--per-chunk") per_chunk = true;
    else if (a == "--method") only_method = next();
    else if (a == "--only-view") only_view = std::stoi(next());
    else if (a == "--msaa") msaa = static_cast<std::uint32_t>(std::stoi(next()));
    else if (a == "--cull") cull_choice = next();
    else if (a == "--shading") shading_choice = next();
    else if (a == "--anisotropy") anisotropy = std::stoi(next());
    else if (a == "--prepass") prepass_choice = next();
    else if (a == "--shading-pass") pass_choice = next();
    else if (a == "--probe-visibility") visibility = std::stoi(next());
    else path = a;
  }
  if (!only_method.empty() && !raster::parse_view_method(only_method))
    throw std::invalid_argument("--method must be per-view, multiview or layered, not " + only_method);
  if (cull_choice != "on" && cull_choice != "off" && cull_choice != "both")
    throw std::invalid_argument("--cull must be on, off or both, not " + cull_choice);
  std::vector<raster::Shading> shadings;
  if (shading_choice == "both") shadings = {raster::Shading::full, raster::Shading::trivial};
  else if (auto sh = raster::parse_shading(shading_choice)) shadings = {*sh};
  else throw std::invalid_argument("--shading must be full, trivial or both, not " + shading_choice);
  std::vector<std::optional<bool>> prepasses;
  if (prepass_choice == "auto") prepasses = {std::nullopt};
  else if (prepass_choice == "on") prepasses = {true};
  else if (prepass_choice == "off") prepasses = {false};
  else if (prepass_choice == "both") prepasses = {true, false};
  else throw std::invalid_argument("--prepass must be auto, on, off or both, not " + prepass_choice);
  std::vector<std::optional<raster::ShadingPass>> passes;
  if (pass_choice == "auto") passes = {std::nullopt};
  else if (pass_choice == "both") passes = {raster::ShadingPass::forward, raster::ShadingPass::visibility};
  else if (const auto p = raster::parse_shading_pass(pass_choice)) passes = {*p};
  else throw std::invalid_argument("--shading-pass must be auto, forward, visibility or both, not " + pass_choice);
  raster::check_anisotropy(anisotropy);
  const scene::Scene s = scene::load_scene(path);
  gpu::Context context({.application_name = "raster_views"});
  gpu::Device& device = context.device();
  probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {4, 4, 4}), 2, visibility);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i)
    for (glm::vec2& m : volume.moments(i)) m = {0.2f, 0.05f};
  std::printf("# %s, %zu mesh triangles (before instancing), %dx%d, device %s, %d frames (median), "
              "anisotropy option %d\n", path.c_str(),
              [&] { std::size_t t = 0; for (const auto& m : s.meshes) t += m.triangle_count(); return t; }(),
              width, height, device.info().name.c_str(), frames, anisotropy);
  std::printf("method,cull,shading,prepass,shading_pass,views,passes,frame_ms,ms_per_view,forward_gpu_ms,record_ms,"
              "cpu_ms,triangles,draws,readback_ms\n");
  // Every configuration renders each frame in turn (paired runs): on a shared machine the load
  // changes from minute to minute, and interleaving spreads it evenly over the configurations.
  struct Config {
    raster::ViewMethod method;
    bool cull;
    raster::Shading shading;
    bool prepass;
    raster::ShadingPass pass;
    std::unique_ptr<raster::Renderer> renderer;
    std::vector<double> frame, gpu, record, cpu, readback;
    raster::FrameStats last;
  };
  std::vector<Config> configs;
  for (raster::ViewMethod method :
       {raster::ViewMethod::per_view, raster::ViewMethod::multiview, raster::ViewMethod::layered})
    for (bool cull : {false, true})
      for (raster::Shading shading : shadings)
        for (std::optional<bool> prepass : prepasses)
          for (std::optional<raster::ShadingPass> pass : passes) {
            if (!only_method.empty() && only_method != raster::to_string(method)) continue;
            if (cull_choice != "both" && cull != (cull_choice == "on")) continue;
            // The trivial floor never has a prepass and is always the forward pass: one row.
            if (shading == raster::Shading::trivial && (prepass != prepasses.front() || pass != passes.front()))
              continue;
            // The visibility pass has no prepass: one row of it.
            if (pass == raster::ShadingPass::visibility && prepass != prepasses.front()) continue;
            raster::RendererOptions options;
            options.msaa = msaa;
            options.view_method = method;
            options.cull = cull;
            options.anisotropy = anisotropy;
            options.shading = shading;
            options.depth_prepass = prepass;
            options.shading_pass = pass;
            auto renderer = std::make_unique<raster::Renderer>(device, s, volume, options);
            const bool on = renderer->depth_prepass();
            configs.push_back({method, cull, shading, on, renderer->shading_pass(), std::move(renderer), {}, {}, {},
                               {}, {}});
          }
  for (int n : counts) {
    std::vector<scene::View> all_views = rig(s, n, width, height);
    if (only_view >= 0) all_views = {all_views.at(static_cast<std::size_t>(only_view))};
    // The frame's render() calls: all views at once, or chunks of --chunk views.
    const std::size_t step = chunk > 0 ? std::size_t(chunk) : all_views.size();
    auto render_frame = [&](raster::Renderer& r) {
      raster::FrameStats sum;
      for (std::size_t first = 0; first < all_views.size(); first += step) {
        const std::size_t count = std::min(step, all_views.size() - first);
        const raster::FrameStats st = r.render(s, std::span(all_views).subspan(first, count)).stats;
        if (per_chunk)
          std::fprintf(stderr, "chunk %zu..%zu forward_gpu_ms %.1f first eye %.4f,%.4f,%.4f\n", first,
                       first + count - 1, st.forward_gpu_ms, all_views[first].eye().x,
                       all_views[first].eye().y, all_views[first].eye().z);
        sum.forward_passes += st.forward_passes;
        sum.cull += st.cull;
        sum.record_ms += st.record_ms;
        sum.execute_ms += st.execute_ms;
        sum.readback_ms += st.readback_ms;
        sum.forward_gpu_ms += st.forward_gpu_ms;
      }
      return sum;
    };
    for (Config& c : configs) {
      render_frame(*c.renderer);  // warm-up: target, pipelines, shadow maps
      c.frame.clear();
      c.gpu.clear();
      c.record.clear();
      c.cpu.clear();
      c.readback.clear();
    }
    for (int f = 0; f < frames; ++f)
      for (Config& c : configs) {
        // Process CPU time (all threads, lavapipe's included): on a shared machine it counts
        // this frame's work, not the time other processes took.
        const double cpu0 = process_cpu_ms();
        const raster::FrameStats st = render_frame(*c.renderer);
        c.cpu.push_back(process_cpu_ms() - cpu0);
        c.last = st;
        c.frame.push_back(st.record_ms + st.execute_ms + st.readback_ms);
        c.gpu.push_back(st.forward_gpu_ms);
        c.record.push_back(st.record_ms);
        c.readback.push_back(st.readback_ms);
      }
    for (const Config& c : configs) {
      const double ms = median(c.frame);
      std::printf("%s,%s,%s,%s,%s,%d,%u,%.2f,%.2f,%.2f,%.2f,%.2f,%llu,%llu,%.2f\n",
                  std::string(raster::to_string(c.method)).c_str(), c.cull ? "on" : "off",
                  std::string(raster::to_string(c.shading)).c_str(), c.prepass ? "on" : "off",
                  std::string(raster::to_string(c.pass)).c_str(), n,
                  c.last.forward_passes, ms, ms / n, median(c.gpu), median(c.record), median(c.cpu),
                  static_cast<unsigned long long>(c.last.cull.triangles_drawn),
                  static_cast<unsigned long long>(c.last.cull.draws), median(c.readback));
    }
    std::fflush(stdout);
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "raster_views: %s\n", e.what());
  return 1;
}
