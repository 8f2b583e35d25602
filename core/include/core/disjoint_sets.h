#pragma once
// Union–find over indices 0..n−1 whose representative is always a set's smallest index, so
// that what callers derive from it does not depend on the order of the unions.

#include <cstdint>
#include <numeric>
#include <vector>

namespace penumbra {

class DisjointSets {
public:
    explicit DisjointSets(std::size_t n) : parent_(n) {
        std::iota(parent_.begin(), parent_.end(), std::uint32_t(0));
    }
    /// The smallest index of \p i's set (path halving).
    std::uint32_t find(std::uint32_t i) {
        while (parent_[i] != i)
            i = parent_[i] = parent_[parent_[i]];
        return i;
    }
    void unite(std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a < b)
            parent_[b] = a;
        else
            parent_[a] = b;
    }

private:
    std::vector<std::uint32_t> parent_;
};

} // namespace penumbra
