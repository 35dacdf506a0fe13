// Sums over the points into nodal (or matrix) entries, split among threads without locks: each
// thread takes a contiguous block of points and adds into its own zeroed copy of the entries;
// reduce() adds the copies in thread order. For a given thread count the result is the same to the
// last bit from run to run; with one thread it is the serial sum in point order.
#pragma once

#include <omp.h>

#include <cstddef>
#include <exception>
#include <span>
#include <stdexcept>
#include <vector>

#include "numerics/parallel.hpp"

namespace unsatmpm::numerics {

class ThreadSums {
 public:
  /// Threads of the next scatter (>= 1).
  void set_threads(int n_threads) {
    if (n_threads < 1) throw std::invalid_argument("ThreadSums: threads must be >= 1");
    n_threads_ = n_threads;
  }

  /// body(p, sum) for every p in [0, n_points), where sum is the calling thread's copy of `size`
  /// entries, zeroed before its first point. An exception thrown by body is rethrown here after
  /// the threads have joined (the first thread's in thread order).
  template <class Body>
  void scatter(std::size_t n_points, std::size_t size, Body&& body) {
    copies_.resize(static_cast<std::size_t>(n_threads_));
    errors_.assign(static_cast<std::size_t>(n_threads_), nullptr);
    size_ = size;
    used_ = 1;
    parallel_region(n_threads_, [&] {
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
      const auto n = static_cast<std::size_t>(omp_get_num_threads());
      if (t == 0) used_ = static_cast<int>(n);
      try {
        std::vector<double>& sum = copies_[t];
        sum.assign(size, 0.0);
        const std::size_t begin = n_points * t / n, end = n_points * (t + 1) / n;
        for (std::size_t p = begin; p < end; ++p) body(p, std::span<double>(sum));
      } catch (...) {
        errors_[t] = std::current_exception();
      }
    });
    for (const auto& e : errors_)
      if (e) std::rethrow_exception(e);
  }

  /// The copies of the last scatter added in thread order.
  std::span<const double> reduce() {
    std::vector<double>& total = copies_[0];
    const auto n = static_cast<std::size_t>(used_);
    if (n > 1) {
      const auto size = static_cast<std::ptrdiff_t>(size_);
      parallel_region(used_, [&] {
#pragma omp for schedule(static)
        for (std::ptrdiff_t k = 0; k < size; ++k)
          for (std::size_t t = 1; t < n; ++t)
            total[static_cast<std::size_t>(k)] += copies_[t][static_cast<std::size_t>(k)];
      });
    }
    return {total.data(), size_};
  }

 private:
  int n_threads_ = 1;
  int used_ = 1;  // threads the last scatter had
  std::size_t size_ = 0;
  std::vector<std::vector<double>> copies_;
  std::vector<std::exception_ptr> errors_;
};

}  // namespace unsatmpm::numerics
