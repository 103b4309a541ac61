#pragma once
//! \file disjoint_sets.h
//! \brief Union-find over 0..n-1 with path halving; the root of a set is its lowest member,
//! so results never depend on the order of the unions (deterministic ids).

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace polycube::core {

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n = 0) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  //! Root (lowest member) of the set of x.
  int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  //! Merge the sets of a and b. \return false when they were one set already.
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

 private:
  std::vector<int> parent_;
};

}  // namespace polycube::core
