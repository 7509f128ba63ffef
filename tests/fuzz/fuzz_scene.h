// The glTF and GLB targets' common part: load the file as `ddish info` and `ddish render` do
// (textures decoded, no sidecar: that has a target of its own), then build what the renderer
// derives from the model: SceneFeatures, the render plan, a pose at another time, the bounds.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "scene/features.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"

namespace fuzz {

inline void load_scene_file(const std::uint8_t* data, std::size_t size, const char* name) {
  const std::string path = as_file(data, size, name);
  accepts([&] {
    ddish::scene::Scene s = ddish::scene::load_scene(
        path, {.decode_textures = true, .read_sidecar = false, .decode_threads = 1});
    const ddish::scene::SceneFeatures features = ddish::scene::analyze(s);
    const ddish::scene::RenderPlan plan = ddish::scene::make_plan(features);
    if (plan.left_out.size() > 32) finding("implausible render plan", name);
    s.pose(0.5);
    const ddish::scene::Aabb b = s.bounds();
    // A loaded scene is finite: the loader rejects non-finite positions and transforms.
    if (!b.empty())
      for (int a = 0; a < 3; ++a)
        if (!std::isfinite(b.min[a]) || !std::isfinite(b.max[a]))
          finding("non-finite bounds of a loaded scene", name);
  });
}

}  // namespace fuzz
