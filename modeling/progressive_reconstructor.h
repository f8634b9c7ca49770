#pragma once
// Progressive reconstruction (thesis 4.6): the sketching session's stateful reconstructor.
//
// It keeps the bounding box fixed while sketching (the box is set by the first update and
// replaced only when a point leaves it) and caches the union solid of every zone, keyed by the
// zone's primitives (which encode the zone's geometry and every section and extension touching
// it). Adding, editing or deleting a section therefore recomputes only the unions of the zones
// whose primitives changed; the stitching of zones is redone (it is linear in the surface size).
//
// Order independence: curves are sorted canonically before anything else and zones are merged
// in zone order, so the same set of sections gives the bit-identical mesh whatever order they
// were added in (given the same box).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include "modeling/aligned_frame.h"
#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/reconstruct.h"
#include "modeling/status.h"
#include "modeling/topology_edit.h"

namespace ps {

struct ValidatedSections;

class ProgressiveReconstructor {
 public:
  explicit ProgressiveReconstructor(ReconstructOptions options = {});

  // Reconstructs the whole current set. On error the previous state (box, cache, last mesh) is
  // unchanged.
  Result<TriMesh> update(const SectionSet& sections, ReconstructReport* report = nullptr);

  // Editing helpers on the reconstructor's own copy of the set (each calls update()).
  Result<TriMesh> add(const Plane& plane, const std::vector<Vec3>& curve, ReconstructReport* report = nullptr);
  Result<TriMesh> replace(int curve, const std::vector<Vec3>& points, ReconstructReport* report = nullptr);
  Result<TriMesh> remove(int curve, ReconstructReport* report = nullptr);

  // Topology editing (thesis 6.4, topology_edit.h), on sections of axis planes (or of planes in
  // at most three orthogonal directions, which run on the grid in their own frame,
  // aligned_frame.h; the strokes stay in world coordinates): the edit is kept
  // and applied again on every later update (a kept edit that no longer applies, because the
  // sections changed under it, is skipped with a warning). On error nothing changes.
  Result<TriMesh> join(const std::vector<Vec3>& stroke, ReconstructReport* report = nullptr);
  Result<TriMesh> split(const std::vector<Vec3>& stroke, ReconstructReport* report = nullptr);
  // Removes the last edit and reconstructs.
  Result<TriMesh> undo_edit(ReconstructReport* report = nullptr);
  const std::vector<TopologyEdit>& edits() const { return edits_; }
  // Reconstructs `sections` with exactly these edits (e.g. a loaded session, the command line);
  // every edit must apply.
  Result<TriMesh> update(const SectionSet& sections, const std::vector<TopologyEdit>& edits,
                         ReconstructReport* report = nullptr);

  const SectionSet& sections() const { return sections_; }
  const TriMesh& mesh() const { return mesh_; }
  const Box3& box() const { return box_; }
  // Fix the box explicitly (e.g. the app's drawing volume). Clears the cache.
  void set_box(const Box3& box);
  void clear();

 private:
  struct CacheEntry {
    std::vector<TriMesh> primitives;
    TriMesh solid;
  };
  // One run's reusable results: zone unions by primitives, region clippings, cap
  // triangulations and prism checks.
  struct Caches {
    std::multimap<std::uint64_t, CacheEntry> zones;
    ClipCache clips;
    CylinderCache cylinders;
    void clear() { *this = Caches{}; }
  };
  // Edits from index `strict_from` on must apply; earlier ones are skipped with a warning.
  // Planes that a rotation makes axis planes go to the grid in that frame first; if that fails
  // (rounding in the frame), to the convex zones of chapter 6 in the world frame.
  Result<TriMesh> update_with(const SectionSet& sections, const std::vector<TopologyEdit>& edits,
                              std::size_t strict_from, ReconstructReport* report);
  Result<TriMesh> update_in_frame(const SectionSet& sections, const std::vector<TopologyEdit>& edits,
                                  std::size_t strict_from, ReconstructReport* report, bool allow_frame,
                                  bool* used_frame);
  Result<TriMesh> reconstruct_grid(const ValidatedSections& scaled, const Box3& box, double tol, int scale_exponent,
                                   const std::vector<TopologyEdit>& edits, std::size_t strict_from,
                                   ReconstructReport& rep, const std::function<void(const char*, double)>& progress,
                                   Caches& next_cache) const;
  ReconstructOptions options_;
  SectionSet sections_;
  TriMesh mesh_;
  Box3 box_;  // in frame_'s coordinates
  bool box_fixed_ = false;
  AlignedFrame frame_;  // of the last update (identity for axis planes and for chapter 6)
  Caches cache_;
  std::vector<TopologyEdit> edits_;
};

}  // namespace ps
