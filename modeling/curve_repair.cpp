#include "modeling/curve_repair.h"

// Written by hand rather than with CGAL's arrangements: the curves are small (tens to a few
// thousand points), every decision uses the exact orientation predicate of polyline_crossing.h,
// and the only constructions are a crossing point and a moved contact vertex, both checked
// exactly at the end. A CGAL arrangement with winding numbers would handle curves whose loops
// cross each other after the split; none of the real data sets needs it (docs/formats.md).

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

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
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = j + 2; k < n; ++k) {
      if (j == 0 && k == n - 1) continue;  // neighbours through the closing edge
      if (!boxes[j].overlaps(boxes[k])) continue;
      const V& a = l[j];
      const V& b = l[(j + 1) % n];
      const V& c = l[k];
      const V& d = l[(k + 1) % n];
      if (!segments_intersect(a.p, b.p, c.p, d.p)) continue;
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
      return ct;
    }
  }
  return std::nullopt;
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
  std::vector<Box> bb(nb);
  Box all_b{1e300, -1e300, 1e300, -1e300};
  for (std::size_t j = 0; j < nb; ++j) {
    bb[j] = seg_box(b[j].p, b[(j + 1) % nb].p);
    all_b = {std::min(all_b.x0, bb[j].x0), std::max(all_b.x1, bb[j].x1), std::min(all_b.y0, bb[j].y0),
             std::max(all_b.y1, bb[j].y1)};
  }
  for (std::size_t i = 0; i < na; ++i) {
    const Vec2& p = a[i].p;
    const Vec2& q = a[(i + 1) % na].p;
    const Box bi = seg_box(p, q);
    if (!bi.overlaps(all_b)) continue;
    for (std::size_t j = 0; j < nb; ++j) {
      if (!bi.overlaps(bb[j])) continue;
      const Vec2& r = b[j].p;
      const Vec2& s = b[(j + 1) % nb].p;
      if (segments_intersect(p, q, r, s)) return PairContact{i, j, proper_crossing(p, q, r, s)};
    }
  }
  return std::nullopt;
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
  std::stable_sort(r.loops.begin(), r.loops.end(), [](const Loop& a, const Loop& b) {
    return std::abs(signed_area(a)) > std::abs(signed_area(b));
  });

  // 4. Separate touching loops: the smaller one's contact vertex moves into it.
  std::size_t total = 0;
  for (const Loop& l : r.loops) total += l.size();
  for (std::size_t guard = 0;; ++guard) {
    if (guard > 4 * total + 16) return Result<Repaired>::error("its loops keep touching after separation");
    bool any = false;
    for (std::size_t i = 0; i < r.loops.size() && !any; ++i) {
      for (std::size_t j = i + 1; j < r.loops.size() && !any; ++j) {
        const auto pc = find_pair_contact(r.loops[i], r.loops[j]);
        if (!pc) continue;
        any = true;
        Loop& big = r.loops[i];
        Loop& small = r.loops[j];  // sorted: j is not larger
        const std::size_t nb = big.size(), ns = small.size();
        const Vec2 bp = big[pc->ea].p, bq = big[(pc->ea + 1) % nb].p;
        const Vec2 sp = small[pc->eb].p, sq = small[(pc->eb + 1) % ns].p;
        if (pc->proper) {
          std::ostringstream m;
          const Vec2 x = line_intersection(bp, bq, sp, sq);
          m << "crosses itself twice between the same parts near (" << x.x() << ", " << x.y() << ")";
          return Result<Repaired>::error(m.str());
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
        r.largest_move = std::max(r.largest_move, move_inward(small, v, o, diagonal));
        ++r.separated;
      }
    }
    if (!any) break;
  }

  // The result, checked exactly: every loop simple, no two touching.
  std::vector<std::vector<Vec2>> flat;
  for (const Loop& l : r.loops) {
    flat.emplace_back();
    for (const V& v : l) flat.back().push_back(v.p);
    if (flat.back().size() < 3 || first_self_crossing(flat.back()))
      return Result<Repaired>::error("a loop still crosses itself after the repair");
  }
  for (std::size_t i = 0; i < flat.size(); ++i)
    for (std::size_t j = i + 1; j < flat.size(); ++j)
      if (first_crossing_between(flat[i], flat[j]))
        return Result<Repaired>::error("two of its loops still touch after the repair");
  return r;
}

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

}  // namespace

Result<std::vector<std::vector<Vec2>>> repair_closed_curve(const std::vector<Vec2>& curve,
                                                           const CurveRepairOptions& options) {
  Loop l;
  for (std::size_t i = 0; i < curve.size(); ++i) l.push_back(V{curve[i], static_cast<int>(i)});
  auto r = repair(l, options);
  if (!r) return Result<std::vector<std::vector<Vec2>>>::error(r.message());
  std::vector<std::vector<Vec2>> out;
  for (const Loop& loop : r->loops) {
    out.emplace_back();
    for (const V& v : loop) out.back().push_back(v.p);
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
  return repaired;
}

}  // namespace ps
