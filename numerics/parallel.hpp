// OpenMP parallel regions that cost nothing on one thread.
//
// libgomp ends every parallel region, and every worksharing loop inside one, with a barrier whose
// last thread wakes the others by a futex system call, also in a team of one thread. On the
// explicit cycle's 1D column (512 points, one thread) that was 39 system calls a step and about
// 15 % of its time (perf, 2026-12-01). A worksharing loop outside any parallel region (orphaned)
// runs whole on the calling thread without a barrier. So the kernels write their region's body as
// a function whose loops carry `#pragma omp for`: parallel_region runs it in a region on two or
// more threads and calls it directly on one. Variables declared in the body are private to each
// thread, those it captures by reference shared, as in a region; reductions go on the loops.
#pragma once

namespace unsatmpm::numerics {

/// Runs body() on n_threads OpenMP threads, or directly on the calling thread if n_threads <= 1.
template <class Body>
void parallel_region(int n_threads, Body&& body) {
  if (n_threads <= 1) {
    body();
    return;
  }
#pragma omp parallel num_threads(n_threads)
  body();
}

}  // namespace unsatmpm::numerics
