// The shading's feature switches, specialization constants 0..5 (raster/shader_variant.h),
// shared by the forward shading, its masked depth prepass (forward_material.glsl) and any pass
// that evaluates include/surface_lighting.glsl.
#ifndef DDISH_FORWARD_VARIANT_GLSL
#define DDISH_FORWARD_VARIANT_GLSL

// Variants chosen from scene::SceneFeatures (raster/shader_variant.h): a scene pays only for
// what it has; the compiler removes the dead branches.
layout(constant_id = 0) const bool kDirectLights = true;
layout(constant_id = 1) const bool kShadows = true;
layout(constant_id = 2) const bool kTextures = true;
layout(constant_id = 3) const bool kSpecularProbes = true;
layout(constant_id = 4) const bool kProbes = true;
layout(constant_id = 5) const bool kEmission = true;

#endif
