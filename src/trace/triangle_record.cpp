#include "trace/triangle_record.h"

#include "scene/scene.h"
#include "trace/surface.h"

namespace ddish::trace {

std::vector<TriangleRecord> make_triangle_records(const scene::Mesh& mesh) {
  const std::size_t vertices = mesh.positions.size();
  std::uint32_t flags = 0;
  if (mesh.normals.size() == vertices) flags |= TriangleRecord::kNormals;
  if (mesh.uvs.size() == vertices) flags |= TriangleRecord::kUvs;
  if (mesh.tangents.size() == vertices) flags |= TriangleRecord::kTangents;
  std::vector<TriangleRecord> records(mesh.triangle_count());
  for (std::size_t k = 0; k < records.size(); ++k) {
    TriangleRecord& r = records[k];
    r.flags = flags;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t i = mesh.indices[3 * k + static_cast<std::size_t>(c)];
      r.p[c] = mesh.positions[i];
      if ((flags & TriangleRecord::kNormals) != 0) r.n[c] = mesh.normals[i];
      if ((flags & TriangleRecord::kUvs) != 0) r.uv[c] = mesh.uvs[i];
      if ((flags & TriangleRecord::kTangents) != 0) r.t[c] = mesh.tangents[i];
    }
    r.uv_area = uv_area(mesh, static_cast<int>(k), 0);
  }
  return records;
}

}  // namespace ddish::trace
