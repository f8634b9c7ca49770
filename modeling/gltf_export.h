#pragma once
// glTF 2.0 binary (.glb) export of a triangle mesh: one buffer with float32 positions, float32
// per-vertex normals (area-weighted face normals) and uint32 indices; one mesh with one
// triangle primitive, one node, one scene. POSITION carries the min/max the spec requires
// (computed from the float32 values actually stored). Chunks are padded to 4 bytes (JSON with
// spaces, BIN with zeros).
//
// Hand-written because Debian 12 packages no glTF writer library (tinygltf, cgltf and
// fx-gltf are not in the archive); the format is small and fully specified.
#include <cstdint>
#include <string>
#include <vector>

#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

// The .glb bytes, or an error for an empty mesh, a non-finite or float-overflowing
// coordinate, or a face index out of range.
Result<std::vector<std::uint8_t>> encode_glb(const TriMesh& mesh);

// Writes encode_glb(mesh) to `path` through a temporary file renamed into place.
Status write_glb(const std::string& path, const TriMesh& mesh);

// Per-vertex unit normals: area-weighted sums of the incident faces' normals (a vertex with
// no incident face, or zero total area, gets (0, 0, 1)).
std::vector<Vec3> vertex_normals(const TriMesh& mesh);

}  // namespace ps
