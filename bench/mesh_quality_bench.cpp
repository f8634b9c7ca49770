// Quality figures of mesh files, as the tables of bench/results/improve.md quote them: faces,
// smallest angle, mean over faces of each face's smallest angle, and the largest and the
// edge-length-weighted RMS dihedral angle, and the shares of edges over 60 and 90 degrees
// (mesh_quality, modeling/mesh_improve.h).
// Usage: mesh_quality_bench MESH [MESH ...]   (.obj .off .ply .stl)
#include <cstdio>

#include "modeling/mesh_improve.h"
#include "modeling/mesh_io.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MESH [MESH ...]\n", argv[0]);
    return 2;
  }
  int failed = 0;
  for (int i = 1; i < argc; ++i) {
    const auto mesh = ps::read_mesh(argv[i]);
    if (!mesh) {
      std::fprintf(stderr, "mesh_quality_bench: %s: %s\n", argv[i], mesh.message().c_str());
      failed = 1;
      continue;
    }
    const ps::MeshQuality q = ps::mesh_quality(*mesh);
    std::printf("%s faces %zu min_angle %.2f mean_min_angle %.1f max_dihedral %.1f rms_dihedral %.2f edges_over_60deg %.2f%% edges_over_90deg %.2f%%\n", argv[i],
                mesh->faces.size(), q.min_angle_deg, q.mean_min_angle_deg, q.max_dihedral_deg, q.rms_dihedral_deg,
                100.0 * q.sharp_edge_share, 100.0 * q.folded_edge_share);
  }
  return failed;
}
