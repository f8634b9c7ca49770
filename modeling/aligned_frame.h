#pragma once
// A rotated frame in which tilted planes become coordinate planes, so that sections on them go
// through the grid of chapter 4 instead of the convex zones of chapter 6.
//
// Cross sections whose planes take at most three mutually orthogonal directions are common: a
// CT or MRI stack acquired with a tilted gantry (one direction, e.g. OReX's SideBishop), a sketch
// on reference planes turned as a whole (up to three). Chapter 6's arrangement of planes and its
// frusta handle them, but the grid of chapter 4 (cuboid zones, straight prisms, parallel
// sections united in 2D, per-zone caches) does the same job several times faster. The thesis
// reconstructs in the world frame; reconstructing in the planes' own frame is our choice
// (docs/reconstruction.md, "Tilted stacks on the grid"). It also makes the result follow a
// rotation of the input, where the world-aligned box of chapter 6 does not.
//
// Conventions:
//   rotation R is proper (det +1); a world point p has frame coordinates R p, and a frame
//   point q is the world point R^T q. Each direction class of the planes' normals maps to a
//   coordinate axis.
//   Two unit normals are one direction when |n1 x n2| <= kAlignedDirectionTolerance and
//   orthogonal when |n1 . n2| <= kAlignedDirectionTolerance; a point moves by at most that
//   fraction of its distance from the origin of the planes when it is put exactly on its axis
//   plane (to_aligned_frame), far below the 1e-6 of the diagonal the reconstruction promises.
#include <optional>

#include <Eigen/Core>

#include "modeling/cross_section.h"

namespace ps {

inline constexpr double kAlignedDirectionTolerance = 1e-9;

struct AlignedFrame {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vec3 to_frame(const Vec3& p) const { return rotation * p; }
  Vec3 to_world(const Vec3& q) const { return rotation.transpose() * q; }
};

// The frame of the planes that hold a curve of `sections` (unit normals, as validate_sections
// leaves them), or nothing when they are already coordinate planes or take more than three
// directions or directions that are not mutually orthogonal. The result depends only on the set
// of those planes' directions: not on the order of planes or curves, nor on the normals' signs.
std::optional<AlignedFrame> aligned_frame(const SectionSet& sections);

// `sections` in `frame`: every plane becomes a coordinate plane (normal +e_k, the offset carried
// over with its sign) and every curve point is rotated and put exactly on its plane (its k-th
// coordinate set to the plane's offset). Planes that hold no curve are dropped; curves keep their
// order. Requires a frame from aligned_frame(sections).
SectionSet to_aligned_frame(const SectionSet& sections, const AlignedFrame& frame);

}  // namespace ps
