// Vertex normals and tangents for meshes whose files do not provide them.
#pragma once

#include "scene/scene.h"

namespace ddish::scene {

// Area-weighted vertex normals from the triangles (the cross product's length is twice the
// area, so summing unnormalised face normals weights them by area). Vertices on no triangle
// get +Y.
void generate_normals(Mesh& mesh);

// Per-vertex tangents as glTF requires for files without them: MikkTSpace's essentials, written
// for ddish (no code taken from the reference implementation).
//  - UVs enter with v flipped (t = 1 - v): glTF's v runs down the image, MikkTSpace's up, and a
//    normal map's green channel is "up" in the image, so the bitangent follows dP/d(1 - v).
//  - Each triangle's tangent is dP/du and its orientation the sign of its UV area (in the flipped
//    space); at each corner the tangent is projected onto the vertex normal's plane, normalised,
//    and weighted by the corner's angle (between the edges projected onto that plane).
//  - Corners of a vertex are accumulated per orientation; a vertex whose triangles disagree
//    (mirrored UVs) is split: the negative group gets a copy of the vertex (every attribute), so
//    each vertex has one handedness. w = ±1: bitangent = w * cross(N, T).
// Simplified against MikkTSpace: vertices are the file's indices (identical vertices under
// different indices are not welded, so their tangents are not shared across the seam); groups
// are "same vertex, same orientation" rather than faces connected around the vertex; triangles
// without a UV gradient contribute nothing and join the vertex's first orientation; a vertex
// left without a tangent gets any unit vector orthogonal to its normal (valid, arbitrary).
// texcoord: the UV set the normal texture reads (0 or 1).
void generate_tangents(Mesh& mesh, int texcoord = 0);

}  // namespace ddish::scene
