// Vertex normals and tangents for meshes whose files do not provide them.
#pragma once

#include "scene/scene.h"

namespace ddish::scene {

// Area-weighted vertex normals from the triangles (the cross product's length is twice the
// area, so summing unnormalised face normals weights them by area). Vertices on no triangle
// get +Y.
void generate_normals(Mesh& mesh);

// Per-vertex tangents from UV gradients, accumulated over the triangles that share a vertex
// (MikkTSpace-like, without its vertex splitting), then made orthogonal to the normal
// (Gram-Schmidt). w = ±1 is the bitangent's handedness: B = w * cross(N, T). Where the UVs are
// degenerate any unit vector orthogonal to the normal is used, so tangents are always valid.
void generate_tangents(Mesh& mesh);

}  // namespace ddish::scene
