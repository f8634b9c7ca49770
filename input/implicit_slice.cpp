// Marching squares with bisection-polished vertices (see implicit_slice.h).
#include "input/implicit_slice.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace ps {

namespace {

// Moves along the segment a-b (fa, fb of opposite inside/outside state) to the zero crossing.
Vec3 bisect(const ScalarField& f, Vec3 a, Vec3 b, double fa) {
  const bool a_inside = fa < 0.0;
  for (int it = 0; it < 80; ++it) {
    const Vec3 m = 0.5 * (a + b);
    if (m == a || m == b) break;
    if ((f(m) < 0.0) == a_inside) a = m;
    else b = m;
  }
  return 0.5 * (a + b);
}

}  // namespace

Result<std::vector<std::vector<Vec3>>> slice_implicit(const ScalarField& field, const Plane& plane,
                                                      const SliceWindow& window) {
  using Loops = std::vector<std::vector<Vec3>>;
  const int n = window.resolution;
  if (n < 4 || n > 8192) return Result<Loops>::error("slice resolution must be in 4..8192");
  if (!(window.half_extent > 0.0) || !std::isfinite(window.half_extent))
    return Result<Loops>::error("slice window half extent must be > 0");
  Vec3 u, v;
  plane.basis(u, v);
  const Vec3 origin = plane.project(window.center) - window.half_extent * (u + v);
  const double h = 2.0 * window.half_extent / n;
  const int m = n + 1;  // grid points per side
  auto point = [&](int i, int j) -> Vec3 { return origin + (i * h) * u + (j * h) * v; };

  // === Field on the grid
  std::vector<double> val(static_cast<std::size_t>(m) * static_cast<std::size_t>(m));
  auto at = [&](int i, int j) -> double& { return val[static_cast<std::size_t>(j) * static_cast<std::size_t>(m) + static_cast<std::size_t>(i)]; };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const double f = field(point(i, j));
      if (!std::isfinite(f)) return Result<Loops>::error("field is not finite on the slice plane");
      at(i, j) = f;
      if ((i == 0 || j == 0 || i == n || j == n) && f < 0.0)
        return Result<Loops>::error("the solid reaches the border of the slice window");
    }

  // === Segments between crossed grid edges
  // Edge ids: horizontal edge (i,j)-(i+1,j) -> 2*(j*m+i); vertical edge (i,j)-(i,j+1) -> 2*(j*m+i)+1.
  auto hid = [&](int i, int j) { return 2 * (static_cast<std::int64_t>(j) * m + i); };
  auto vid = [&](int i, int j) { return 2 * (static_cast<std::int64_t>(j) * m + i) + 1; };
  std::unordered_map<std::int64_t, std::vector<std::int64_t>> adj;
  auto link = [&](std::int64_t a, std::int64_t b) {
    adj[a].push_back(b);
    adj[b].push_back(a);
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool a = at(i, j) < 0, b = at(i + 1, j) < 0, c = at(i + 1, j + 1) < 0, d = at(i, j + 1) < 0;
      const int code = a | (b << 1) | (c << 2) | (d << 3);
      if (code == 0 || code == 15) continue;
      const std::int64_t e0 = hid(i, j), e1 = vid(i + 1, j), e2 = hid(i, j + 1), e3 = vid(i, j);
      // Crossed edges in order around the cell: bottom e0 (a-b), right e1 (b-c), top e2 (d-c), left e3 (a-d).
      std::vector<std::int64_t> crossed;
      if (a != b) crossed.push_back(e0);
      if (b != c) crossed.push_back(e1);
      if (c != d) crossed.push_back(e2);
      if (d != a) crossed.push_back(e3);
      if (crossed.size() == 2) {
        link(crossed[0], crossed[1]);
      } else {
        // Saddle: the corners whose state differs from the centre's are cut off.
        const bool centre = field(point(i, j) + 0.5 * h * (u + v)) < 0;
        if (a != centre) link(e0, e3);
        if (b != centre) link(e0, e1);
        if (c != centre) link(e1, e2);
        if (d != centre) link(e2, e3);
      }
    }

  // === Chain segments into loops, then place each vertex on the zero set
  auto edge_point = [&](std::int64_t id) -> Vec3 {
    const std::int64_t k = id / 2;
    const int i = static_cast<int>(k % m), j = static_cast<int>(k / m);
    const int i2 = (id % 2 == 0) ? i + 1 : i, j2 = (id % 2 == 0) ? j : j + 1;
    return bisect(field, point(i, j), point(i2, j2), at(i, j));
  };
  std::vector<std::int64_t> keys;
  keys.reserve(adj.size());
  for (const auto& kv : adj) {
    if (kv.second.size() != 2) return Result<Loops>::error("slice contour is not a set of closed curves");
    keys.push_back(kv.first);
  }
  std::sort(keys.begin(), keys.end());  // deterministic loop order and start points
  std::unordered_map<std::int64_t, bool> used;
  Loops loops;
  for (std::int64_t start : keys) {
    if (used[start]) continue;
    std::vector<Vec3> loop;
    std::int64_t prev = -1, cur = start;
    while (!used[cur]) {
      used[cur] = true;
      loop.push_back(edge_point(cur));
      const auto& nb = adj[cur];
      const std::int64_t next = nb[0] != prev ? nb[0] : nb[1];
      prev = cur;
      cur = next;
    }
    if (loop.size() >= 3) loops.push_back(std::move(loop));
  }
  auto area = [&](const std::vector<Vec3>& l) {
    double a2 = 0.0;
    for (std::size_t k = 0; k < l.size(); ++k) {
      const Vec3& p = l[k];
      const Vec3& q = l[(k + 1) % l.size()];
      a2 += u.dot(p) * v.dot(q) - u.dot(q) * v.dot(p);
    }
    return std::abs(0.5 * a2);
  };
  std::stable_sort(loops.begin(), loops.end(), [&](const auto& x, const auto& y) { return area(x) > area(y); });
  return loops;
}

}  // namespace ps
