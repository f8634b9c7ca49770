#pragma once
// Results of pure functions keyed by their whole input (compared exactly, found by a 64-bit
// hash), for the progressive reconstructor: a run looks its inputs up in the previous run's
// cache and records everything it used in the next one, so a cache holds exactly one run's
// entries. A hit returns what the computation would return, so cached and fresh runs agree bit
// for bit.
#include <cstdint>
#include <cstring>
#include <map>
#include <utility>
#include <vector>

#include "modeling/mesh.h"

namespace ps {

// FNV-1a over bytes.
struct ContentHash {
  std::uint64_t h = 1469598103934665603ULL;
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  }
  void size(std::size_t n) { bytes(&n, sizeof n); }
  // FNV-1a over one 64-bit word at a time: eight times fewer steps than bytes() for keys made of
  // doubles, hashed often (mesh improvement's face keys). Only the high bits mix in every input
  // bit, so table indices take those (multiply-shift).
  void word(std::uint64_t w) { h = (h ^ w) * 1099511628211ULL; }
  void points(const std::vector<Vec2>& v) {
    size(v.size());
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(Vec2));
  }
  void points(const std::vector<Vec3>& v) {
    size(v.size());
    for (const auto& p : v) bytes(p.data(), sizeof(double) * 3);
  }
  void doubles(const std::vector<double>& v) {
    size(v.size());
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(double));
  }
  void mesh(const TriMesh& m) {
    points(m.vertices);
    size(m.faces.size());
    for (const auto& f : m.faces) bytes(f.data(), sizeof(int) * 3);
  }
};

template <class Key, class Value>
struct ContentCache {
  std::multimap<std::uint64_t, std::pair<Key, Value>> entries;
  const Value* find(std::uint64_t hash, const Key& key) const {
    for (auto [it, end] = entries.equal_range(hash); it != end; ++it)
      if (it->second.first == key) return &it->second.second;
    return nullptr;
  }
};

// The value for `key`: from `previous` when it holds it, else `compute()`; recorded in `next`.
// Either cache may be null.
template <class Key, class Value, class Compute>
Value cached(const ContentCache<Key, Value>* previous, ContentCache<Key, Value>* next, std::uint64_t hash,
             const Key& key, const Compute& compute) {
  const Value* hit = previous ? previous->find(hash, key) : nullptr;
  if (!hit && next) hit = next->find(hash, key);
  Value value = hit ? *hit : compute();
  if (next && !next->find(hash, key)) next->entries.emplace(hash, std::make_pair(key, value));
  return value;
}

}  // namespace ps
