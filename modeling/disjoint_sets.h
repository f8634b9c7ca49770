#pragma once
// Disjoint sets (union-find) over 0..n-1 with path halving. unite(a, b) hangs a's root under
// b's root; callers that only compare roots or collect members do not depend on which element
// ends up the root.
#include <cstddef>
#include <numeric>
#include <vector>

namespace ps {

struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      auto& p = parent[static_cast<std::size_t>(x)];
      p = parent[static_cast<std::size_t>(p)];
      x = p;
    }
    return x;
  }
  void unite(int a, int b) { parent[static_cast<std::size_t>(find(a))] = find(b); }
};

}  // namespace ps
