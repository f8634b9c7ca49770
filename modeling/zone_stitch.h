#pragma once
// Stitching of per-zone solids into one closed surface (thesis 4.2: "stitch all the pieces of
// sub-surfaces together").
//
// Each zone solid lies inside its zone. Its triangles lying in a zone face are cap material on
// that face. For every internal face the material of the two zones sharing it is compared: where
// both sides have material the face is interior and disappears; where only one side has it, that
// side's cap is kept (Q_below XOR Q_above, triangulated by a constrained Delaunay triangulation of
// both sides' cap edges). The remaining triangles are welded by position (tolerance `tol`) and
// T-junctions are removed by splitting edges at vertices lying on them (corefinement may have
// inserted a vertex on one side of a face boundary only).
#include <vector>

#include "modeling/mesh.h"
#include "modeling/status.h"
#include "modeling/polyhedral_partition.h"
#include "modeling/zone_partition.h"

namespace ps {

struct StitchReport {
  int face_triangles_removed = 0;
  int cap_triangles_kept = 0;
  int t_junctions_split = 0;
};

// zone_solids is indexed like partition.zones (empty meshes for zones without material).
// The result may still be open if the zones do not match; the caller checks.
TriMesh stitch_zones(const Partition& partition, const std::vector<TriMesh>& zone_solids, double tol,
                     StitchReport* report = nullptr);

// The same for the convex zones of planes of any orientation (thesis 6.3.3): cap material is
// every triangle lying in a face plane of its zone, bucketed by shared face and compared in the
// plane's 2D frame.
TriMesh stitch_polyhedral_zones(const PolyPartition& partition, const std::vector<TriMesh>& zone_solids, double tol,
                                StitchReport* report = nullptr);

// Splits faces at vertices lying inside their boundary edges (edges used by one face), within
// tol of the edge and more than tol from its ends, so that the vertices of one side of a seam
// become vertices of the other; returns the number of edges split. Faces whose own apex lies on
// the split edge are dropped (flat slivers).
int split_t_junctions(TriMesh& m, double tol);

// Welds vertices closer than tol (first occurrence wins, deterministic), drops faces that became
// degenerate and unreferenced vertices.
TriMesh weld_vertices(const TriMesh& mesh, double tol);

// Local self-intersection check and repair after rounding. Rounding exact results can leave
// two distinct vertices within a few 1e-17 of each other whose fans cross (recon_kernel corpus
// seed valid_three_axes); elsewhere rounding moves points by far less than the features. The
// faces around every vertex that has another vertex within `tol` are tested
// (intersecting_face_pairs); if one intersects, such vertices are merged (smallest index wins,
// degenerate faces dropped) and the faces around the merged vertices are tested again.
// Returns false when an intersection remains (the mesh is then left merged; the caller refuses
// it). The caller checks the topology afterwards.
bool repair_close_vertices(TriMesh& mesh, double tol);

// Canonical order: vertices sorted by (x, y, z), each face rotated to start at its smallest
// index, faces sorted. Two meshes with the same triangles become bit-identical.
void canonicalize(TriMesh& mesh);

}  // namespace ps
