// glTF animations to AnimChannels: keyframe times are checked to be finite and increasing and
// the output accessor to hold one value (three for cubic splines) per key, so sampling never
// reads past its arrays. A "weights" channel's value is one weight per morph target of the
// node's mesh.
#include <cmath>

#include "scene/gltf_internal.h"

namespace ddish::scene::gltf {

void load_animations(const Context& ctx, Scene& scene) {
  const auto& m = ctx.model;
  for (std::size_t a = 0; a < m.animations.size(); ++a) {
    const auto& ga = m.animations[a];
    Animation anim;
    anim.name = ga.name.empty() ? "animation" + std::to_string(a) : ga.name;
    for (std::size_t c = 0; c < ga.channels.size(); ++c) {
      const auto& gc = ga.channels[c];
      const std::string what = "animation '" + anim.name + "' channel " + std::to_string(c);
      AnimChannel ch;
      if (gc.target_path == "translation")
        ch.path = AnimPath::Translation;
      else if (gc.target_path == "rotation")
        ch.path = AnimPath::Rotation;
      else if (gc.target_path == "scale")
        ch.path = AnimPath::Scale;
      else if (gc.target_path == "weights")
        ch.path = AnimPath::Weights;
      else {
        scene.warnings.push_back(what + ": '" + gc.target_path + "' animation is ignored");
        continue;
      }
      if (gc.target_node < 0 || std::size_t(gc.target_node) >= m.nodes.size())
        ctx.fail(what + ": target node " + std::to_string(gc.target_node) + " does not exist");
      if (gc.sampler < 0 || std::size_t(gc.sampler) >= ga.samplers.size())
        ctx.fail(what + ": sampler " + std::to_string(gc.sampler) + " does not exist");
      ch.node = gc.target_node;
      ch.width = ch.path == AnimPath::Rotation ? 4 : 3;
      if (ch.path == AnimPath::Weights) {
        ch.width = int(morph_target_count(ctx, gc.target_node));
        if (ch.width == 0) {
          scene.warnings.push_back(what + ": 'weights' animation of a node without morph targets is ignored");
          continue;
        }
      }
      const auto& gs = ga.samplers[std::size_t(gc.sampler)];
      if (gs.interpolation == "STEP")
        ch.interpolation = Interpolation::Step;
      else if (gs.interpolation == "LINEAR" || gs.interpolation.empty())
        ch.interpolation = Interpolation::Linear;
      else if (gs.interpolation == "CUBICSPLINE")
        ch.interpolation = Interpolation::CubicSpline;
      else
        ctx.fail(what + ": unknown interpolation '" + gs.interpolation + "'");

      FloatData in = read_floats(ctx, gs.input, what + " input");
      if (in.components != 1 || in.values.empty())
        ctx.fail(what + ": input must be a non-empty list of scalar times");
      for (std::size_t k = 0; k < in.values.size(); ++k)
        if (!std::isfinite(in.values[k]) || (k > 0 && !(in.values[k] > in.values[k - 1])))
          ctx.fail(what + ": key times must be finite and strictly increasing (key " +
                   std::to_string(k) + ")");
      ch.times = std::move(in.values);

      FloatData out = read_floats(ctx, gs.output, what + " output");
      const std::size_t per_key = ch.interpolation == Interpolation::CubicSpline ? 3 : 1;
      // Weights come as scalars, one per target and key; the other paths as vectors.
      const int components = ch.path == AnimPath::Weights ? 1 : ch.width;
      const std::size_t want = ch.times.size() * per_key * std::size_t(ch.width) / std::size_t(components);
      if (out.components != components || out.count() != want)
        ctx.fail(what + ": output holds " + std::to_string(out.count()) + " values of " +
                 std::to_string(out.components) + " components, expected " + std::to_string(want) +
                 " of " + std::to_string(components));
      for (std::size_t k = 0; k < out.values.size(); ++k)
        if (!std::isfinite(out.values[k]))
          ctx.fail(what + ": output value " + std::to_string(k / std::size_t(ch.width)) +
                   " is not finite");
      ch.values = std::move(out.values);
      anim.channels.push_back(std::move(ch));
    }
    scene.animations.push_back(std::move(anim));
  }
}

}  // namespace ddish::scene::gltf
