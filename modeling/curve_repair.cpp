#include "modeling/curve_repair.h"

// Written by hand rather than with CGAL's arrangements: the curves are small (tens to a few
// thousand points), every decision uses the exact orientation predicate of polyline_crossing.h,
// and the only constructions are a crossing point and a moved contact vertex, both checked
// exactly at the end. A CGAL arrangement with winding numbers would handle curves whose loops
// cross each other after the split; none of the real data sets needs it (docs/formats.md).

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>
#include <map>

#include "modeling/disjoint_sets.h"
#include "modeling/polygon_boolean_2.h"
#include "modeling/polyline_crossing.h"
#include "modeling/section_validate.h"

namespace ps {
namespace {

// A loop vertex: its position in the plane's 2D frame and the index of the input point it is
// (so the 3D point can be kept bit for bit), or -1 for a constructed or moved point.
struct V {
  Vec2 p = Vec2::Zero();
  int id = -1;
};
using Loop = std::vector<V>;

double signed_area(const Loop& l) {
  double s = 0.0;
  for (std::size_t i = 0; i < l.size(); ++i) {
    const Vec2& a = l[i].p;
    const Vec2& b = l[(i + 1) % l.size()].p;
    s += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * s;
}

void drop_repeated(Loop& l) {
  Loop out;
  out.reserve(l.size());
  for (const V& v : l)
    if (out.empty() || out.back().p != v.p) out.push_back(v);
  while (out.size() > 1 && out.front().p == out.back().p) out.pop_back();
  l.swap(out);
}

struct Box {
  double x0, x1, y0, y1;
  bool overlaps(const Box& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
};
Box seg_box(const Vec2& a, const Vec2& b) {
  return {std::min(a.x(), b.x()), std::max(a.x(), b.x()), std::min(a.y(), b.y()), std::max(a.y(), b.y())};
}

// The bounding box of a loop's points.
Box loop_box(const std::vector<Vec2>& loop) {
  Box b{1e300, -1e300, 1e300, -1e300};
  for (const Vec2& q : loop) b = {std::min(b.x0, q.x()), std::max(b.x1, q.x()), std::min(b.y0, q.y()), std::max(b.y1, q.y())};
  return b;
}

// Calls pair(i, j), i < j, for every two boxes that overlap, found by a sweep over x (near
// linear for a curve's edges, whose boxes are small); stops at the first call returning true.
template <class F>
bool sweep_overlaps(const std::vector<Box>& boxes, F&& pair) {
  std::vector<std::size_t> order(boxes.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return boxes[a].x0 < boxes[b].x0 || (boxes[a].x0 == boxes[b].x0 && a < b);
  });
  for (std::size_t a = 0; a < order.size(); ++a) {
    const Box& ba = boxes[order[a]];
    for (std::size_t b = a + 1; b < order.size() && boxes[order[b]].x0 <= ba.x1; ++b) {
      const Box& bb = boxes[order[b]];
      if (bb.y0 > ba.y1 || bb.y1 < ba.y0) continue;
      if (pair(std::min(order[a], order[b]), std::max(order[a], order[b]))) return true;
    }
  }
  return false;
}

// Whether p lies on the closed segment [a, b] (exact).
bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  if (orient2d(a, b, p) != 0) return false;
  const Box bx = seg_box(a, b);
  return bx.x0 <= p.x() && p.x() <= bx.x1 && bx.y0 <= p.y() && p.y() <= bx.y1;
}

bool proper_crossing(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d), o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  return o1 * o2 < 0 && o3 * o4 < 0;
}

Vec2 line_intersection(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Vec2 r = b - a, s = d - c;
  const double den = r.x() * s.y() - r.y() * s.x();
  const double t = ((c - a).x() * s.y() - (c - a).y() * s.x()) / den;
  return a + std::clamp(t, 0.0, 1.0) * r;
}

// === 1. Contacts of a loop with itself
struct Contact {
  enum Kind { kFoldBack, kSplit } kind;
  std::size_t j = 0, k = 0;  // kFoldBack: the spike's tip is vertex j; kSplit: edges j < k
  V x;                       // kSplit: the contact point
};

std::optional<Contact> find_contact(const Loop& l) {
  const std::size_t n = l.size();
  std::vector<Box> boxes(n);
  for (std::size_t i = 0; i < n; ++i) boxes[i] = seg_box(l[i].p, l[(i + 1) % n].p);
  // Fold-backs first: consecutive edges overlapping (a spike), tip at vertex s.
  for (std::size_t s = 0; s < n; ++s) {
    const Vec2& a = l[(s + n - 1) % n].p;
    const Vec2& t = l[s].p;
    const Vec2& b = l[(s + 1) % n].p;
    if (orient2d(a, t, b) == 0 && (a - t).dot(b - t) > 0.0) return Contact{Contact::kFoldBack, s, 0, {}};
  }
  std::optional<Contact> found;
  sweep_overlaps(boxes, [&](std::size_t j, std::size_t k) {
    if (k == j + 1 || (j == 0 && k == n - 1)) return false;  // neighbours: fold-backs above
    const V& a = l[j];
    const V& b = l[(j + 1) % n];
    const V& c = l[k];
    const V& d = l[(k + 1) % n];
    if (!segments_intersect(a.p, b.p, c.p, d.p)) return false;
    Contact ct{Contact::kSplit, j, k, {}};
    if (proper_crossing(a.p, b.p, c.p, d.p)) {
      ct.x = V{line_intersection(a.p, b.p, c.p, d.p), -1};
    } else if (on_segment(c.p, d.p, a.p)) {
      ct.x = a;
    } else if (on_segment(c.p, d.p, b.p)) {
      ct.x = b;
    } else if (on_segment(a.p, b.p, c.p)) {
      ct.x = c;
    } else {
      ct.x = d;
    }
    found = ct;
    return true;
  });
  return found;
}

// The two loops of a split at edges j < k through the contact point x.
std::pair<Loop, Loop> split(const Loop& l, const Contact& c) {
  const std::size_t n = l.size();
  Loop a{c.x}, b{c.x};
  for (std::size_t i = c.j + 1; i <= c.k; ++i) a.push_back(l[i]);
  for (std::size_t i = c.k + 1; i != c.j + 1 + n; ++i) b.push_back(l[i % n]);
  drop_repeated(a);
  drop_repeated(b);
  return {std::move(a), std::move(b)};
}

// === 2. Which loops bound the region (non-zero winding of the input curve)
int winding_number(const std::vector<Vec2>& curve, const Vec2& q) {
  int w = 0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const Vec2& a = curve[i];
    const Vec2& b = curve[(i + 1) % curve.size()];
    if (a.y() <= q.y()) {
      if (b.y() > q.y() && orient2d(a, b, q) > 0) ++w;
    } else if (b.y() <= q.y() && orient2d(a, b, q) < 0) {
      --w;
    }
  }
  return w;
}

bool bounds_region(const Loop& l, const std::vector<Vec2>& curve) {
  // Sample both sides of the loop's longest edge, very close to its midpoint.
  std::size_t best = 0;
  double best_len = -1.0;
  for (std::size_t i = 0; i < l.size(); ++i) {
    const double len = (l[(i + 1) % l.size()].p - l[i].p).norm();
    if (len > best_len) best_len = len, best = i;
  }
  const Vec2 a = l[best].p, b = l[(best + 1) % l.size()].p;
  const Vec2 m = 0.5 * (a + b);
  const Vec2 normal = Vec2(-(b - a).y(), (b - a).x()) / best_len;
  const double h = 1e-7 * best_len;
  const bool left = winding_number(curve, m + h * normal) != 0;
  const bool right = winding_number(curve, m - h * normal) != 0;
  return left != right;
}

// === 4. Separation of loops that touch
struct PairContact {
  std::size_t ea, eb;  // edge indices in loops a and b
  bool proper;
};

std::optional<PairContact> find_pair_contact(const Loop& a, const Loop& b) {
  const std::size_t na = a.size(), nb = b.size();
  std::vector<Box> boxes(na + nb);
  for (std::size_t i = 0; i < na; ++i) boxes[i] = seg_box(a[i].p, a[(i + 1) % na].p);
  for (std::size_t j = 0; j < nb; ++j) boxes[na + j] = seg_box(b[j].p, b[(j + 1) % nb].p);
  std::optional<PairContact> found;
  sweep_overlaps(boxes, [&](std::size_t i, std::size_t k) {
    if (i >= na || k < na) return false;  // both edges of one loop
    const std::size_t j = k - na;
    const Vec2& p = a[i].p;
    const Vec2& q = a[(i + 1) % na].p;
    const Vec2& r = b[j].p;
    const Vec2& s = b[(j + 1) % nb].p;
    if (!segments_intersect(p, q, r, s)) return false;
    found = PairContact{i, j, proper_crossing(p, q, r, s)};
    return true;
  });
  return found;
}

// Moves vertex v of loop `l` into the loop along the bisector of its inner angle.
double move_inward(Loop& l, std::size_t v, const CurveRepairOptions& o, double diagonal) {
  const std::size_t n = l.size();
  const Vec2 a = l[(v + n - 1) % n].p, x = l[v].p, b = l[(v + 1) % n].p;
  const double la = (a - x).norm(), lb = (b - x).norm();
  const Vec2 u = (a - x) / la, w = (b - x) / lb;
  const double sign = signed_area(l) > 0.0 ? 1.0 : -1.0;
  Vec2 d = u + w;
  if (d.norm() < 1e-12) {
    d = sign * Vec2(-(b - a).y(), (b - a).x());  // straight: the inner normal
  } else if (orient2d(a, x, b) * sign < 0) {
    d = -d;  // a reflex corner: its inner bisector points the other way
  }
  d.normalize();
  const double dist = std::min(o.separation * std::min(la, lb), o.max_separation * diagonal);
  l[v] = V{x + dist * d, -1};
  return dist;
}

// Sorts `loops` by decreasing |area|, then pulls apart every two that touch (the smaller one's
// contact vertex moves into it) and checks the result exactly: every loop simple, no two
// touching. An error names what is left.
Status separate_loops(std::vector<Loop>& loops, const CurveRepairOptions& o, double diagonal, int* separated,
                      double* largest_move) {
  std::stable_sort(loops.begin(), loops.end(), [](const Loop& a, const Loop& b) {
    return std::abs(signed_area(a)) > std::abs(signed_area(b));
  });
  std::size_t total = 0;
  for (const Loop& l : loops) total += l.size();
  for (std::size_t guard = 0;; ++guard) {
    if (guard > 4 * total + 16) return Status::error("its loops keep touching after separation");
    bool any = false;
    for (std::size_t i = 0; i < loops.size() && !any; ++i) {
      for (std::size_t j = i + 1; j < loops.size() && !any; ++j) {
        const auto pc = find_pair_contact(loops[i], loops[j]);
        if (!pc) continue;
        any = true;
        Loop& big = loops[i];
        Loop& small = loops[j];  // sorted: j is not larger
        const std::size_t nb = big.size(), ns = small.size();
        const Vec2 bp = big[pc->ea].p, bq = big[(pc->ea + 1) % nb].p;
        const Vec2 sp = small[pc->eb].p, sq = small[(pc->eb + 1) % ns].p;
        if (pc->proper) {
          std::ostringstream m;
          const Vec2 x = line_intersection(bp, bq, sp, sq);
          m << "crosses itself twice between the same parts near (" << x.x() << ", " << x.y() << ")";
          return Status::error(m.str());
        }
        std::size_t v;
        if (on_segment(bp, bq, sp)) {
          v = pc->eb;
        } else if (on_segment(bp, bq, sq)) {
          v = (pc->eb + 1) % ns;
        } else {
          // A vertex of the larger loop on the smaller loop's edge: make it a vertex there.
          const V& at = on_segment(sp, sq, bp) ? big[pc->ea] : big[(pc->ea + 1) % nb];
          small.insert(small.begin() + static_cast<std::ptrdiff_t>(pc->eb + 1), at);
          v = pc->eb + 1;
        }
        *largest_move = std::max(*largest_move, move_inward(small, v, o, diagonal));
        ++*separated;
      }
    }
    if (!any) break;
  }
  std::vector<std::vector<Vec2>> flat;
  for (const Loop& l : loops) {
    flat.emplace_back();
    for (const V& v : l) flat.back().push_back(v.p);
    if (flat.back().size() < 3 || first_self_crossing(flat.back()))
      return Status::error("a loop still crosses itself after the repair");
  }
  for (std::size_t i = 0; i < flat.size(); ++i)
    for (std::size_t j = i + 1; j < flat.size(); ++j)
      if (first_crossing_between(flat[i], flat[j])) return Status::error("two of its loops still touch after the repair");
  return Status::ok();
}

std::vector<std::vector<Vec2>> points_of(const std::vector<Loop>& loops) {
  std::vector<std::vector<Vec2>> out;
  for (const Loop& l : loops) {
    out.emplace_back();
    for (const V& v : l) out.back().push_back(v.p);
  }
  return out;
}

struct Repaired {
  std::vector<Loop> loops;  // largest |area| first
  int dropped_tiny = 0, dropped_redundant = 0, separated = 0;
  double largest_dropped_fraction = 0.0, largest_move = 0.0;
};

Result<Repaired> repair(const Loop& input, const CurveRepairOptions& o) {
  std::vector<Vec2> curve;
  curve.reserve(input.size());
  for (const V& v : input) {
    if (!v.p.allFinite()) return Result<Repaired>::error("has a non-finite point");
    curve.push_back(v.p);
  }
  Vec2 lo = curve.empty() ? Vec2::Zero() : curve[0], hi = lo;
  for (const Vec2& p : curve) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double diagonal = (hi - lo).norm();
  if (!(diagonal > 0.0) || !std::isfinite(diagonal)) return Result<Repaired>::error("has no extent");

  // 1. Split at contacts until every loop is simple.
  Repaired r;
  std::vector<Loop> stack{input};
  drop_repeated(stack.back());
  std::size_t steps = 0;
  const std::size_t max_steps = 8 * input.size() + 64;
  std::vector<Loop> simple;
  while (!stack.empty()) {
    if (++steps > max_steps) return Result<Repaired>::error("too many contacts to split");
    Loop l = std::move(stack.back());
    stack.pop_back();
    if (l.size() < 3) continue;  // a spike or a loop of no area
    const auto c = find_contact(l);
    if (!c) {
      if (signed_area(l) != 0.0) simple.push_back(std::move(l));
      continue;
    }
    if (c->kind == Contact::kFoldBack) {
      l.erase(l.begin() + static_cast<std::ptrdiff_t>(c->j));
      drop_repeated(l);
      stack.push_back(std::move(l));
    } else {
      auto [a, b] = split(l, *c);
      stack.push_back(std::move(a));
      stack.push_back(std::move(b));
    }
  }
  if (simple.empty()) return Result<Repaired>::error("encloses no area once its contacts are split");

  // 2-3. Keep the loops that bound the region and are not negligibly small.
  double largest = 0.0;
  for (const Loop& l : simple) largest = std::max(largest, std::abs(signed_area(l)));
  for (Loop& l : simple) {
    const double fraction = std::abs(signed_area(l)) / largest;
    if (fraction < o.min_area_fraction) {
      ++r.dropped_tiny;
      r.largest_dropped_fraction = std::max(r.largest_dropped_fraction, fraction);
    } else if (!bounds_region(l, curve)) {
      ++r.dropped_redundant;
    } else {
      r.loops.push_back(std::move(l));
    }
  }
  if (r.loops.empty()) return Result<Repaired>::error("no loop of it bounds its region");

  // 4. Separate touching loops: the smaller one's contact vertex moves into it.
  if (const Status st = separate_loops(r.loops, o, diagonal, &r.separated, &r.largest_move); !st)
    return Result<Repaired>::error(st.message());
  return r;
}

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

// The boundary loops of a region given as polygons with holes (polygon_boolean_2.h); a loop
// that touches itself (CGAL keeps a pinch inside one loop) is split as a curve of its own would
// be. Vertex ids are 0 ("look the point up"); split failures go to *status.
std::vector<Loop> boundary_loops(const std::vector<std::vector<std::vector<Vec2>>>& pieces, const CurveRepairOptions& o,
                                 Status* status) {
  std::vector<Loop> out;
  for (const auto& piece : pieces)
    for (const auto& loop : piece) {
      Loop l;
      std::vector<Vec2> pts;
      for (const Vec2& q : loop) l.push_back(V{q, 0}), pts.push_back(q);
      drop_repeated(l);
      if (!first_self_crossing(pts)) {
        out.push_back(std::move(l));
        continue;
      }
      auto r = repair(l, o);
      if (!r) {
        *status = Status::error("its boundary " + r.message());
        continue;
      }
      for (Loop& part : r->loops) out.push_back(std::move(part));
    }
  return out;
}

// === 5. Curves of one plane that cross or touch each other
// Whether most vertices of `a` lie inside the simple loop `b` (vertices on b count for neither).
bool mostly_inside(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  int in = 0, out = 0;
  const std::size_t step = std::max<std::size_t>(1, a.size() / 16);  // a sample of 16 vertices
  for (std::size_t k = 0; k < a.size(); k += step) {
    const Vec2& q = a[k];
    bool on = false;
    for (std::size_t i = 0; i < b.size() && !on; ++i) on = on_segment(b[i], b[(i + 1) % b.size()], q);
    if (on) continue;
    (winding_number(b, q) != 0 ? in : out)++;
  }
  return in > out;
}

// Replaces each group of curves of a plane that cross or touch one another by the boundary of
// the region they make together: curves at even depth (counted among the plane's curves, by
// most of their vertices) add their inside, curves at odd depth take it away, in order of
// depth. Returns the number of groups replaced.
int merge_crossing_curves(SectionSet& sections, std::vector<std::string>* warnings, const CurveRepairOptions& o) {
  int merged = 0;
  std::vector<char> erase(sections.curves.size(), 0);
  for (std::size_t pl = 0; pl < sections.planes.size(); ++pl) {
    std::vector<int> idx;
    for (std::size_t c = 0; c < sections.curves.size(); ++c) {
      const CrossSection& cs = sections.curves[c];
      bool finite = cs.points.size() >= 3;
      for (const Vec3& p : cs.points) finite = finite && p.allFinite();
      if (cs.plane == static_cast<int>(pl) && finite) idx.push_back(static_cast<int>(c));
    }
    if (idx.size() < 2) continue;
    const PlaneFrame frame = plane_frame(sections.planes[pl]);
    const std::size_t n = idx.size();
    std::vector<std::vector<Vec2>> flat(n);
    std::vector<Box> box(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (const Vec3& p : sections.curves[static_cast<std::size_t>(idx[i])].points) flat[i].push_back(frame.to_2d(p));
      box[i] = loop_box(flat[i]);
    }
    DisjointSets crossing(n);
    bool any = false;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (box[i].overlaps(box[j]) && first_crossing_between(flat[i], flat[j])) {
          crossing.unite(static_cast<int>(i), static_cast<int>(j));
          any = true;
        }
    if (!any) continue;
    std::vector<std::vector<int>> groups(n);
    for (std::size_t i = 0; i < n; ++i) groups[static_cast<std::size_t>(crossing.find(static_cast<int>(i)))].push_back(static_cast<int>(i));
    for (const auto& group : groups) {
      if (group.size() < 2) continue;
      // Depth among all curves of the plane.
      std::vector<std::pair<int, int>> by_depth;  // (depth, position in idx)
      for (int gi : group) {
        int depth = 0;
        for (std::size_t k = 0; k < n; ++k)
          if (static_cast<int>(k) != gi && box[k].overlaps(box[static_cast<std::size_t>(gi)]) &&
              mostly_inside(flat[static_cast<std::size_t>(gi)], flat[k]))
            ++depth;
        by_depth.emplace_back(depth, gi);
      }
      std::stable_sort(by_depth.begin(), by_depth.end());
      const int d0 = by_depth.front().first;
      std::vector<std::vector<Vec2>> loops;
      std::vector<bool> add;
      std::vector<const CrossSection*> inputs;
      for (const auto& [depth, gi] : by_depth) {
        loops.push_back(flat[static_cast<std::size_t>(gi)]);
        add.push_back((depth - d0) % 2 == 0);
        inputs.push_back(&sections.curves[static_cast<std::size_t>(idx[static_cast<std::size_t>(gi)])]);
      }
      Status split_status = Status::ok();
      std::vector<Loop> out = boundary_loops(boolean_of_loops(loops, add), o, &split_status);
      Vec2 lo(box[static_cast<std::size_t>(group[0])].x0, box[static_cast<std::size_t>(group[0])].y0), hi = lo;
      for (int gi : group) {
        const Box& b = box[static_cast<std::size_t>(gi)];
        lo = lo.cwiseMin(Vec2(b.x0, b.y0)), hi = hi.cwiseMax(Vec2(b.x1, b.y1));
      }
      int separated = 0;
      double moved = 0.0;
      std::vector<int> names;
      for (int gi : group) names.push_back(idx[static_cast<std::size_t>(gi)]);
      std::sort(names.begin(), names.end());
      std::ostringstream list;
      for (std::size_t k = 0; k < names.size(); ++k) list << (k ? (k + 1 == names.size() ? " and " : ", ") : "") << names[k];
      const Status st = split_status ? separate_loops(out, o, (hi - lo).norm(), &separated, &moved) : split_status;
      if (!st || out.empty()) {
        if (warnings)
          warnings->push_back("curves " + list.str() + " on plane " + std::to_string(pl) +
                              " cross each other and were not merged: " + (st ? "nothing is left of them" : st.message()));
        continue;
      }
      std::vector<CrossSection> curves = lift_loops(points_of(out), inputs, frame, static_cast<int>(pl));
      std::ostringstream m;
      m << "curves " << list.str() << " on plane " << pl << " cross or touch each other: replaced by the "
        << curves.size() << " curve" << (curves.size() > 1 ? "s" : "") << " bounding their region";
      if (separated > 0) m << "; " << separated << " contact(s) separated by up to " << fmt(moved);
      for (std::size_t k = 0; k < names.size(); ++k) {
        if (k < curves.size()) sections.curves[static_cast<std::size_t>(names[k])] = std::move(curves[k]);
        else erase[static_cast<std::size_t>(names[k])] = 1;
      }
      for (std::size_t k = names.size(); k < curves.size(); ++k) {
        sections.curves.push_back(std::move(curves[k]));
        erase.push_back(0);
      }
      if (warnings) warnings->push_back(m.str());
      ++merged;
    }
  }
  std::vector<CrossSection> kept;
  for (std::size_t c = 0; c < sections.curves.size(); ++c)
    if (!erase[c]) kept.push_back(std::move(sections.curves[c]));
  if (kept.size() != sections.curves.size() && warnings)
    warnings->push_back("curves were renumbered: " + std::to_string(sections.curves.size() - kept.size()) +
                        " merged away");
  sections.curves = std::move(kept);
  return merged;
}


}  // namespace

Result<std::vector<std::vector<Vec2>>> repair_closed_curve(const std::vector<Vec2>& curve,
                                                           const CurveRepairOptions& options) {
  Loop l;
  for (std::size_t i = 0; i < curve.size(); ++i) l.push_back(V{curve[i], static_cast<int>(i)});
  auto r = repair(l, options);
  if (!r) return Result<std::vector<std::vector<Vec2>>>::error(r.message());
  return points_of(r->loops);
}

std::vector<CrossSection> lift_loops(const std::vector<std::vector<Vec2>>& loops,
                                     const std::vector<const CrossSection*>& inputs, const PlaneFrame& frame, int plane) {
  std::map<std::pair<double, double>, Vec3> original;  // an input point's 2D image -> the point
  for (const CrossSection* c : inputs)
    for (const Vec3& p : c->points) {
      const Vec2 q = frame.to_2d(p);
      original.emplace(std::make_pair(q.x(), q.y()), p);
    }
  std::vector<CrossSection> out;
  for (const auto& loop : loops) {
    CrossSection cs;
    cs.plane = plane;
    for (const Vec2& q : loop) {
      const auto it = original.find({q.x(), q.y()});
      cs.points.push_back(it != original.end() ? it->second : frame.to_3d(q));
    }
    out.push_back(std::move(cs));
  }
  return out;
}

int repair_section_curves(SectionSet& sections, std::vector<std::string>* warnings,
                          const CurveRepairOptions& options) {
  int repaired = 0;
  const std::size_t original = sections.curves.size();
  for (std::size_t c = 0; c < original; ++c) {
    const CrossSection& curve = sections.curves[c];
    if (curve.plane < 0 || curve.plane >= static_cast<int>(sections.planes.size()) || curve.points.size() < 3)
      continue;  // validation names these
    bool finite = true;
    for (const Vec3& p : curve.points) finite = finite && p.allFinite();
    if (!finite) continue;
    const PlaneFrame frame = plane_frame(sections.planes[static_cast<std::size_t>(curve.plane)]);
    Loop l;
    std::vector<Vec2> flat;
    for (std::size_t i = 0; i < curve.points.size(); ++i) {
      l.push_back(V{frame.to_2d(curve.points[i]), static_cast<int>(i)});
      flat.push_back(l.back().p);
    }
    if (!first_self_crossing(flat)) continue;
    auto r = repair(l, options);
    if (!r) {
      if (warnings) warnings->push_back("curve " + std::to_string(c) + " touches or crosses itself and was not repaired: it " + r.message());
      continue;
    }
    std::vector<CrossSection> loops;
    for (const Loop& loop : r->loops) {
      CrossSection s;
      s.plane = curve.plane;
      for (const V& v : loop)
        s.points.push_back(v.id >= 0 ? curve.points[static_cast<std::size_t>(v.id)] : frame.to_3d(v.p));
      loops.push_back(std::move(s));
    }
    std::ostringstream m;
    m << "curve " << c << " touched or crossed itself: repaired into " << loops.size() << " simple curve"
      << (loops.size() > 1 ? "s" : "");
    if (loops.size() > 1) {
      m << " (added as curve" << (loops.size() > 2 ? "s " : " ") << sections.curves.size();
      if (loops.size() > 2) m << "-" << sections.curves.size() + loops.size() - 2;
      m << ")";
    }
    if (r->dropped_tiny > 0)
      m << "; " << r->dropped_tiny << " loop" << (r->dropped_tiny > 1 ? "s" : "") << " under " << fmt(100.0 * options.min_area_fraction)
        << "% of its area dropped (largest " << fmt(100.0 * r->largest_dropped_fraction) << "%)";
    if (r->dropped_redundant > 0) m << "; " << r->dropped_redundant << " loop(s) inside the region dropped";
    if (r->separated > 0) m << "; " << r->separated << " contact(s) separated by up to " << fmt(r->largest_move);
    sections.curves[c] = std::move(loops[0]);
    for (std::size_t i = 1; i < loops.size(); ++i) sections.curves.push_back(std::move(loops[i]));
    if (warnings) warnings->push_back(m.str());
    ++repaired;
  }
  return repaired + merge_crossing_curves(sections, warnings, options);
}

bool components_agree_with_nesting(const std::vector<CslComponent>& comps) {
  const std::size_t n = comps.size();
  std::vector<Box> box(n);
  std::vector<char> crosses(n, 0);  // crosses itself or another component of its label
  for (std::size_t i = 0; i < n; ++i) {
    if (comps[i].loop.size() < 3) return true;  // validation's case
    if (first_self_crossing(comps[i].loop)) crosses[i] = 1;
    box[i] = loop_box(comps[i].loop);
  }
  // Two materials that cross or share a boundary disagree with nesting (their union is the
  // object). Components of one label that cross or touch have no clean depth: they are left
  // out of the test (validation refuses them, --repair merges them by nesting), as are
  // components that cross themselves.
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (box[i].overlaps(box[j]) && first_crossing_between(comps[i].loop, comps[j].loop)) {
        if (comps[i].label != comps[j].label) return false;
        crosses[i] = crosses[j] = 1;
      }
  for (std::size_t i = 0; i < n; ++i) {
    if (crosses[i]) continue;
    int depth = 0;
    for (std::size_t j = 0; j < n; ++j)
      if (i != j && box[i].overlaps(box[j]) && mostly_inside(comps[i].loop, comps[j].loop)) ++depth;
    const bool outside_material = comps[i].hole || comps[i].label == 0;
    if ((depth % 2 == 1) != outside_material) return false;
  }
  return true;
}

Result<std::vector<std::vector<Vec2>>> region_of_components(const std::vector<CslComponent>& comps,
                                                            const CurveRepairOptions& options) {
  using R = Result<std::vector<std::vector<Vec2>>>;
  Vec2 lo(1e300, 1e300), hi(-1e300, -1e300);
  // Each component as simple loops: one that crosses itself is split as --repair would
  // (non-zero winding), since its plane is rebuilt as a union anyway.
  std::vector<std::vector<std::vector<Vec2>>> comp_loops(comps.size());
  for (std::size_t i = 0; i < comps.size(); ++i) {
    const auto& l = comps[i].loop;
    bool finite = l.size() >= 3;
    for (const Vec2& q : l) finite = finite && q.allFinite(), lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    if (!finite) return R::error("component " + std::to_string(i) + " has fewer than 3 points or a non-finite one");
    if (comps[i].hole && (comps[i].parent < 0 || comps[i].parent >= static_cast<int>(comps.size())))
      return R::error("component " + std::to_string(i) + " is a hole of no component");
    if (!first_self_crossing(l)) {
      comp_loops[i].push_back(l);
      continue;
    }
    auto fixed = repair_closed_curve(l, options);
    if (!fixed) return R::error("component " + std::to_string(i) + " crosses itself and " + fixed.message());
    comp_loops[i] = std::move(*fixed);
  }
  std::vector<RegionPart> parts;
  std::vector<std::vector<Vec2>> subtract;
  for (std::size_t i = 0; i < comps.size(); ++i) {
    if (comps[i].hole) continue;
    if (comps[i].label == 0) {
      subtract.insert(subtract.end(), comp_loops[i].begin(), comp_loops[i].end());
      continue;
    }
    RegionPart part;
    part.add = comp_loops[i];
    for (std::size_t h = 0; h < comps.size(); ++h)
      if (comps[h].hole && comps[h].parent == static_cast<int>(i))
        part.remove.insert(part.remove.end(), comp_loops[h].begin(), comp_loops[h].end());
    parts.push_back(std::move(part));
  }
  Status status = Status::ok();
  std::vector<Loop> out = boundary_loops(union_of_parts(parts, subtract), options, &status);
  int separated = 0;
  double moved = 0.0;
  if (status) status = separate_loops(out, options, (hi - lo).norm(), &separated, &moved);
  if (!status) return R::error("their union: " + status.message());
  return points_of(out);
}

bool loop_mostly_inside(const std::vector<Vec2>& a, const std::vector<Vec2>& b) { return mostly_inside(a, b); }

}  // namespace ps
