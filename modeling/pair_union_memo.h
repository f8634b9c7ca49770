#pragma once
// Remembered outcomes of union_snapped_solids on pairs of frusta within one zone.
//
// Why: a zone whose first union is refused runs two repairs, connectors
// (frustum_connectors.h) and nudges (frustum_nudge.h), and each first asks, for every pair of
// frusta sharing bottom points, whether the pair's own union is accepted. They ask about the
// same unchanged pairs, and each answer is an exact corefinement (stress seed 218: 14 such
// zones, three frustum attempts each). union_snapped_solids is deterministic, so an answer can
// be reused for a pair with the same content: the memo compares the solids themselves
// (equal vertex coordinates, faces and tags), never addresses or hashes, so a changed frustum (a
// nudged top) is never answered from the memo.
//
// One memo per zone and per attempt; not thread-safe (a zone runs on one thread).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "modeling/zone_union.h"

namespace ps {

class PairUnionMemo {
 public:
  explicit PairUnionMemo(const std::vector<Plane>& planes) : planes_(planes) {}

  // Whether union_snapped_solids({a, b}, planes) succeeds; computed on the first request for
  // this pair (in this order) and remembered.
  bool unites(const SnappedSolid& a, const SnappedSolid& b);

  std::size_t hits() const { return hits_; }
  std::size_t computed() const { return entries_.size(); }

 private:
  struct Entry {
    SnappedSolid a, b;
    bool ok = false;
  };
  const std::vector<Plane>& planes_;
  std::vector<Entry> entries_;
  std::size_t hits_ = 0;
};

// The same solid: equal vertex coordinates, faces and tags.
bool same_solid(const SnappedSolid& a, const SnappedSolid& b);

// A yes/no property of a solid snapped to planes (a pure function of both), remembered by
// content: the last `capacity` solids asked about, compared in full (a hash only picks the
// candidates). Used by union_snapped_solids for the exact self-intersection test of each operand,
// which it runs on every call: a zone whose union is refused asks for many unions of the same
// frusta (connector and nudge pairs, the union at once, the other orders), and on stress seed
// 218 those tests were 34% of the whole reconstruction (perf, one thread). Not thread-safe: one
// per thread.
class SolidVerdicts {
 public:
  explicit SolidVerdicts(std::size_t capacity = 256) : capacity_(capacity) {}
  // The remembered verdict, or -1 when this solid on these planes was not asked about.
  int find(const SnappedSolid& s, const std::vector<Plane>& planes) const;
  void add(const SnappedSolid& s, const std::vector<Plane>& planes, bool verdict);
  std::size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    std::uint64_t hash = 0;
    SnappedSolid solid;
    std::vector<Plane> planes;
    bool verdict = false;
  };
  std::size_t capacity_;
  std::vector<Entry> entries_;  // oldest first
};

}  // namespace ps
