#include "numerics/sparse_gmres.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace unsatmpm::numerics {

SparseGmres::SparseGmres(int max_iterations) : max_iterations_(max_iterations) {
  if (max_iterations < 1)
    throw std::invalid_argument("SparseGmres: max_iterations must be >= 1, got " +
                                std::to_string(max_iterations));
}

void SparseGmres::set(const SparsePattern& pattern, std::span<const double> values,
                      std::span<const std::int64_t> partner) {
  const auto n = static_cast<std::size_t>(pattern.n);
  if (static_cast<std::int64_t>(values.size()) != pattern.n_nonzeros() || partner.size() != n)
    throw std::invalid_argument("SparseGmres: " + std::to_string(values.size()) + " values and " +
                                std::to_string(partner.size()) + " partners for a pattern of " +
                                std::to_string(pattern.n_nonzeros()) + " entries, " +
                                std::to_string(n) + " unknowns");
  pattern_ = nullptr;  // until the blocks are inverted: a failed set leaves nothing to solve with
  partner_.assign(partner.begin(), partner.end());
  own_.resize(n), cross_.resize(n);
  const auto entry = [&](std::int64_t r, std::int64_t c) {
    const std::int64_t e = pattern.position(r, c);
    return e < pattern.row_ptr[r + 1] && pattern.col[e] == c ? values[e] : 0.0;
  };
  for (std::int64_t k = 0; k < pattern.n; ++k) {
    const std::int64_t p = partner_[k];
    const double a = entry(k, k);
    if (p < 0) {
      if (!(std::abs(a) > 0.0))
        throw std::runtime_error("SparseGmres: zero diagonal in row " + std::to_string(k));
      own_[k] = 1.0 / a, cross_[k] = 0.0;
      continue;
    }
    if (p >= pattern.n || partner_[p] != k)
      throw std::invalid_argument("SparseGmres: the partner of " + std::to_string(k) +
                                  " is not mutual");
    // Row k of the inverse of [[a, b], [c, d]] (k first): (d, -b) / det.
    const double b = entry(k, p), c = entry(p, k), d = entry(p, p);
    const double det = a * d - b * c;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det))
      throw std::runtime_error("SparseGmres: singular diagonal block at rows " + std::to_string(k) +
                               ", " + std::to_string(p));
    own_[k] = d / det, cross_[k] = -b / det;
  }
  pattern_ = &pattern, values_ = values;
  const auto m = static_cast<std::size_t>(max_iterations_);
  basis_.resize((m + 1) * n), scratch_.resize(n), product_.resize(n);
  hessenberg_.resize((m + 1) * m), cosine_.resize(m), sine_.resize(m), rotated_.resize(m + 1);
}

bool SparseGmres::solve(std::span<const double> b, std::span<const double> w, std::span<double> x,
                        int n_threads) {
  if (pattern_ == nullptr) throw std::logic_error("SparseGmres: solve before set");
  const auto n = static_cast<std::size_t>(pattern_->n);
  if (b.size() != n || w.size() != n || x.size() != n)
    throw std::invalid_argument("SparseGmres: vectors of " + std::to_string(b.size()) + ", " +
                                std::to_string(w.size()) + ", " + std::to_string(x.size()) +
                                " entries for " + std::to_string(n) + " unknowns");
  n_threads_ = std::max(1, n_threads);
  const int m = max_iterations_;
  const auto vector = [&](int i) { return std::span<double>(basis_).subspan(i * n, n); };
  const auto column = [&](int j) { return hessenberg_.data() + j * (m + 1); };
  // v_0 = W (b - A x) / beta.
  std::span<double> v = vector(0);
  multiply(x.data(), v.data());
  for (std::size_t k = 0; k < n; ++k) v[k] = w[k] * (b[k] - v[k]);
  const double beta = std::sqrt(dot(v, v));
  if (beta <= 1.0) return true;  // the start is within the tolerance: x stays
  for (double& e : v) e /= beta;
  std::fill(rotated_.begin(), rotated_.end(), 0.0);
  rotated_[0] = beta;
  for (int j = 0; j < m; ++j) {
    // The next direction W A P^-1 W^-1 v_j, orthogonalised against the basis.
    const std::span<const double> vj = vector(j);
    for (std::size_t k = 0; k < n; ++k) scratch_[k] = vj[k] / w[k];
    precondition(scratch_.data(), product_.data());
    std::span<double> u = vector(j + 1);
    multiply(product_.data(), u.data());
    for (std::size_t k = 0; k < n; ++k) u[k] *= w[k];
    double* h = column(j);
    for (int i = 0; i <= j; ++i) {
      const std::span<const double> vi = vector(i);
      h[i] = dot(vi, u);
      for (std::size_t k = 0; k < n; ++k) u[k] -= h[i] * vi[k];
    }
    h[j + 1] = std::sqrt(dot(u, u));
    if (h[j + 1] > 0.0)
      for (double& e : u) e /= h[j + 1];
    // The earlier rotations on the new column, then the one that clears h[j + 1].
    for (int i = 0; i < j; ++i) {
      const double a = h[i], c = h[i + 1];
      h[i] = cosine_[i] * a + sine_[i] * c;
      h[i + 1] = -sine_[i] * a + cosine_[i] * c;
    }
    const double r = std::hypot(h[j], h[j + 1]);
    if (!(r > 0.0) || !std::isfinite(r)) {  // a singular or broken projection
      iterations_ += j + 1;
      return false;
    }
    cosine_[j] = h[j] / r, sine_[j] = h[j + 1] / r;
    h[j] = r, h[j + 1] = 0.0;
    rotated_[j + 1] = -sine_[j] * rotated_[j];
    rotated_[j] *= cosine_[j];
    // |rotated_[j + 1]| is the weighted residual's norm after j + 1 iterations.
    if (std::abs(rotated_[j + 1]) <= 1.0) {
      iterations_ += j + 1;
      add_update(j + 1, w, x);
      return true;
    }
  }
  iterations_ += m;
  return false;
}

void SparseGmres::add_update(int k, std::span<const double> w, std::span<double> x) {
  const auto n = x.size();
  const int m = max_iterations_;
  // y from the triangular system R y = g (R: the rotated Hessenberg's first k columns), in place.
  std::vector<double>& y = rotated_;
  for (int i = k - 1; i >= 0; --i) {
    double s = y[i];
    for (int j = i + 1; j < k; ++j) s -= hessenberg_[j * (m + 1) + i] * y[j];
    y[i] = s / hessenberg_[i * (m + 1) + i];
  }
  std::fill(scratch_.begin(), scratch_.end(), 0.0);
  for (int i = 0; i < k; ++i) {
    const double* vi = basis_.data() + i * n;
    for (std::size_t e = 0; e < n; ++e) scratch_[e] += y[i] * vi[e];
  }
  for (std::size_t e = 0; e < n; ++e) scratch_[e] /= w[e];
  precondition(scratch_.data(), product_.data());
  for (std::size_t e = 0; e < n; ++e) x[e] += product_[e];
}

void SparseGmres::multiply(const double* v, double* z) const {
  const auto n = static_cast<std::size_t>(pattern_->n);
  numerics::multiply(*pattern_, values_, {v, n}, {z, n}, n_threads_);
}

void SparseGmres::precondition(const double* r, double* z) const {
  for (std::size_t k = 0; k < own_.size(); ++k) {
    const std::int64_t p = partner_[k];
    z[k] = own_[k] * r[k] + (p >= 0 ? cross_[k] * r[p] : 0.0);
  }
}

}  // namespace unsatmpm::numerics
