// The points' weight-only stencils, evaluated once per relaxation of the pressure offsets and read
// by both fluids' passes, five loops over the points each (numerics/pressure_offsets.hpp,
// numerics/offset_bounds.hpp). Evaluated in every loop, as before 2026-12-02, the stencils'
// assembly took a tenth of the explicit cycle's time on the embankment (perf, docs/performance.md).
// The entries are TransferStencil<D, K, false>'s to the last bit: the same weights of the same
// nodes in the same order, so the relaxation's sums are unchanged.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "numerics/material_points.hpp"
#include "numerics/parallel.hpp"
#include "numerics/shape_functions.hpp"

namespace unsatmpm::numerics {

/// One point's stencil as read from the cache: its entries' count, weights, slots (the entry's
/// place in the kernel's full tensor layout, x fastest) and nodes.
struct CachedStencil {
  int n;
  const double* w;
  const std::int8_t* slots;
  std::int64_t first;                // the node of slot 0
  const std::int64_t* slot_to_node;  // slot -> node - first
  int slot(int k) const { return slots[k]; }
  std::int64_t node(int k) const { return first + slot_to_node[slots[k]]; }
};

/// Per point: its stencil's entries at a stride of the kernel's capacity, their count, its slot-0
/// node and its offset from that node in cells, (x_p - x_0) / h per direction. A node is stored as
/// its slot (one byte) and found from the slot-0 node: 9 bytes an entry, where its index would
/// take 17 (a 3D GIMP point's 27 entries and the rest take 0.28 kB, against 0.49 kB).
struct StencilCache {
  std::vector<double> w;
  std::vector<std::int8_t> slots, count;
  std::vector<std::int64_t> first;
  std::vector<double> offset;
  std::vector<std::int64_t> slot_to_node;
  int capacity = 0, dimension = 0;

  CachedStencil operator[](std::int64_t p) const {
    const std::size_t e = static_cast<std::size_t>(p) * static_cast<std::size_t>(capacity);
    return {count[static_cast<std::size_t>(p)], w.data() + e, slots.data() + e,
            first[static_cast<std::size_t>(p)], slot_to_node.data()};
  }
  /// Throws std::logic_error unless the cache holds n points' stencils (fill_stencils): a cache of
  /// another set of points would be read out of its bounds.
  void require(std::size_t n) const {
    if (count.size() != n)
      throw std::logic_error("StencilCache: filled for another set of points (fill_stencils)");
  }
  /// Point p's offset from its slot-0 node in cells, along direction a.
  double offset_of(std::int64_t p, int a) const {
    return offset[static_cast<std::size_t>(p * dimension + a)];
  }
};

/// Evaluates the stencils of every point of `mp` on `grid` into `cache` (through the points'
/// kernel memo, prepared here).
template <int D, class K>
void fill_stencils(const Grid<D>& grid, const MaterialPoints<D>& mp, int n_threads,
                   StencilCache& cache) {
  constexpr int cap = stencil_capacity<D, K>;
  const std::int64_t n_mp = static_cast<std::int64_t>(mp.size());
  const std::size_t n = static_cast<std::size_t>(n_mp);
  cache.capacity = cap, cache.dimension = D;
  cache.w.resize(n * cap), cache.slots.resize(n * cap), cache.count.resize(n);
  cache.first.resize(n), cache.offset.resize(n * D);
  cache.slot_to_node.resize(cap);
  for (int s = 0; s < cap; ++s) {
    std::int64_t node = 0;
    for (int a = 0, r = s; a < D; ++a, r /= K::n_support)
      node += (r % K::n_support) * grid.stride[a];
    cache.slot_to_node[static_cast<std::size_t>(s)] = node;
  }
  mp.kernel_memo.prepare(grid, mp.size());
  parallel_region(n_threads, [&] {
    TransferStencil<D, K, false> st;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      evaluate_stencil<D, K>(st, grid, mp, p);
      const std::size_t e = static_cast<std::size_t>(p) * cap;
      const std::int64_t first = st.node[0] - cache.slot_to_node[st.slot(0)];
      for (int k = 0; k < st.n; ++k)
        cache.w[e + k] = st.w[k], cache.slots[e + k] = static_cast<std::int8_t>(st.slot(k));
      cache.count[static_cast<std::size_t>(p)] = static_cast<std::int8_t>(st.n);
      cache.first[static_cast<std::size_t>(p)] = first;
      const Vec<D> base = (mp.position[p] - grid.node_position(first)).cwiseQuotient(grid.spacing);
      for (int a = 0; a < D; ++a) cache.offset[static_cast<std::size_t>(p) * D + a] = base[a];
    }
  });
}

}  // namespace unsatmpm::numerics
