// Between the points and the nodes of the pressure system: the nodal start values of an
// integration, fitted to the points' pressures (the first) or to what they depart from the field
// the flow reached (the later ones), and the nodal increments of an integration returned to the
// points.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "numerics/fluid_points.hpp"
#include "numerics/pressure/quadrature.hpp"

namespace unsatmpm::numerics {

/// The least spread, in grid spacings, that the points around a node must have in every direction
/// for their pressures to be fitted linearly there (else their mean). With 2 points per cell and
/// direction, a node on the body's edge sees a spread of 0.22 h across it; a single row of
/// points, 0.
inline constexpr double min_fit_spread = 0.1;

/// The nodal values of the points' pressures. The volume-weighted mean is biased wherever a
/// node's support is one-sided — on the body's boundary: a linear field P = rho g depth
/// projects to rho g h/4 instead of 0 at the surface node, and the flow would start from that
/// error (a spurious flux toward the node, a jump where a prescribed value switches on). So each
/// node takes the value of a weighted least-squares linear fit to the points around it (exact
/// for linear fields, equal to the mean for a symmetric support). The mean stays where the
/// points cannot carry a fit: too few of them, or spread less than min_fit_spread h (weighted
/// standard deviation of their offsets) in some direction. Such a cloud is nearly a line, and
/// the fit's slope across it, extrapolated to the node, is noise: on the embankment a crest
/// squeezed into one column of points (offsets from the node 0.084-0.11 m in x, 0.2 m cells)
/// gave a fitted 3.59 MPa where the points held -71 to +8 kPa (mean -12.3 kPa); the flow
/// started from it and threw the crest out of the grid (t = 138.6 s).
/// Fills `nodal` (liquid, gas; every node, 0 where inactive) [Pa] from the points' `values`
/// (liquid, gas; one per point).
template <int D, class K>
void fit_to_nodes(const Grid<D>& grid, const PointQuadrature<D, K>& q,
                  const std::array<std::span<const double>, 2>& values,
                  std::array<std::vector<double>, 2>& nodal) {
  for (auto& v : nodal) v.assign(grid.n_nodes(), 0.0);
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    const double v = q.volume[p];
    for (int a = 0; a < st.n; ++a) {
      nodal[liquid_phase][st.node[a]] += st.w[a] * v * values[liquid_phase][p];
      nodal[gas_phase][st.node[a]] += st.w[a] * v * values[gas_phase][p];
    }
  }
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
    for (int a = 0; a < 2; ++a)
      if (q.active(i)) nodal[a][i] /= q.node_volume[i];

  using Row = Eigen::Matrix<double, D + 1, 1>;
  using Normal = Eigen::Matrix<double, D + 1, D + 1>;
  std::vector<std::int64_t> fitted;
  std::vector<std::int64_t> slot(grid.n_nodes(), -1);
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
    if (q.active(i)) slot[i] = static_cast<std::int64_t>(fitted.size()), fitted.push_back(i);
  std::vector<Normal> normal(fitted.size(), Normal::Zero());
  std::vector<std::array<Row, 2>> rhs(fitted.size(), {Row::Zero(), Row::Zero()});
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    for (int a = 0; a < st.n; ++a) {
      const auto k = slot[st.node[a]];
      if (k < 0 || st.w[a] <= 0.0) continue;
      Row r;
      r[0] = 1.0;
      r.template tail<D>() = q.position[p] - grid.node_position(st.node[a]);
      const double w = st.w[a] * q.volume[p];
      normal[k] += w * r * r.transpose();
      rhs[k][0] += w * values[liquid_phase][p] * r;
      rhs[k][1] += w * values[gas_phase][p] * r;
    }
  }
  const double min_variance = std::pow(min_fit_spread * grid.spacing.minCoeff(), 2);
  for (std::size_t k = 0; k < fitted.size(); ++k) {
    // Weighted covariance of the offsets, sum w d d^T / sum w - mean mean^T; at least
    // min_variance in every direction also makes the normal matrix invertible (too few points
    // fail here too).
    const double w = normal[k](0, 0);
    const Vec<D> mean = normal[k].template block<D, 1>(1, 0) / w;
    const Eigen::Matrix<double, D, D> cov =
        normal[k].template block<D, D>(1, 1) / w - mean * mean.transpose();
    if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>>(cov, Eigen::EigenvaluesOnly)
            .eigenvalues()
            .minCoeff() < min_variance)
      continue;
    const Eigen::FullPivLU<Normal> lu(normal[k]);
    for (int a = 0; a < 2; ++a) nodal[a][fitted[k]] = lu.solve(rhs[k][a])[0];
  }
}

/// fit_to_nodes of the points' pressures.
template <int D, class K>
void fit_pressures_to_nodes(const Grid<D>& grid, const PointQuadrature<D, K>& q,
                            const FluidPoints<D>& fp, std::array<std::vector<double>, 2>& nodal) {
  fit_to_nodes<D, K>(grid, q, {fp.liquid_pressure, fp.gas_pressure}, nodal);
}

/// A nodal field at the points: P_p = sum_i N_i P_i, per fluid.
template <int D, class K>
void interpolate_nodal(const PointQuadrature<D, K>& q,
                       const std::array<std::vector<double>, 2>& nodal,
                       std::array<std::vector<double>, 2>& at_points) {
  for (auto& v : at_points) v.assign(q.size(), 0.0);
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    for (int a = 0; a < st.n; ++a)
      for (int f = 0; f < 2; ++f) at_points[f][p] += st.w[a] * nodal[f][st.node[a]];
  }
}

/// The nodal start values of a later integration: the field the flow reached (`reached`, at the
/// nodes `had` flags, those active in that integration; the fit of the points' pressures at the
/// others) plus the fit of what the points' pressures depart from it, P_p - sum_i N_i(x_p)
/// reached_i. Fitting the pressures afresh smooths every steep front the flow carries (a wetting
/// front a cell wide in a dry soil): each restart moved water across the front, and on the
/// embankment's face under the surface penalty that fed the mechanics a pressure that tore the
/// still-dry face (verification/embankment/investigations.md, "The screening again
/// with the face's penalty"). The departure holds what moved the points' pressures off the flow's
/// field since (the mechanics' undrained response, as smooth as the loading) plus the fit's
/// residual; the points' values of a nodal field fit back to that field where it is linear, so a
/// flow that restarts with nothing changed starts close to where it stopped. Fills `nodal` as
/// fit_to_nodes does [Pa].
template <int D, class K>
void fit_departure_to_nodes(const Grid<D>& grid, const PointQuadrature<D, K>& q,
                            const FluidPoints<D>& fp,
                            const std::array<std::vector<double>, 2>& reached,
                            const std::vector<std::uint8_t>& had,
                            std::array<std::vector<double>, 2>& nodal) {
  fit_pressures_to_nodes<D, K>(grid, q, fp, nodal);
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
    if (q.active(i) && had[i])
      for (int a = 0; a < 2; ++a) nodal[a][i] = reached[a][i];
  std::array<std::vector<double>, 2> departure;
  interpolate_nodal<D, K>(q, nodal, departure);
  for (std::size_t p = 0; p < q.size(); ++p) {
    departure[liquid_phase][p] = fp.liquid_pressure[p] - departure[liquid_phase][p];
    departure[gas_phase][p] = fp.gas_pressure[p] - departure[gas_phase][p];
  }
  std::array<std::vector<double>, 2> fitted;
  fit_to_nodes<D, K>(grid, q, {departure[liquid_phase], departure[gas_phase]}, fitted);
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
    for (int a = 0; a < 2; ++a) nodal[a][i] += fitted[a][i];
}

/// Where an integration's nodal start values come from (start_values).
enum class StartFrom { points, given, reached };

/// The nodal start values (`nodal`: a field of every node, per fluid): fitted to the points'
/// pressures (fit_pressures_to_nodes); `nodal` as it is (those of a flow that ran before at this
/// configuration); or `nodal` as the integration before reached it at the nodes `had` flags, with
/// the fit of what the points depart from it (fit_departure_to_nodes). Throws
/// std::invalid_argument if `from` needs a `nodal` (and for `reached` a `had`) of the grid's size
/// and has none.
template <int D, class K>
void start_values(StartFrom from, const Grid<D>& grid, const PointQuadrature<D, K>& q,
                  const FluidPoints<D>& fp, const std::array<std::vector<double>, 2>* nodal,
                  const std::vector<std::uint8_t>& had, std::array<std::vector<double>, 2>& out) {
  const auto n = static_cast<std::size_t>(grid.n_nodes());
  if (from != StartFrom::points && !(nodal && (*nodal)[0].size() == n && (*nodal)[1].size() == n))
    throw std::invalid_argument("start_values: no nodal field of the grid's size to start from");
  if (from == StartFrom::reached && had.size() != n)
    throw std::invalid_argument("start_values: the nodes of the integration before not given");
  if (from == StartFrom::given)
    out = *nodal;
  else if (from == StartFrom::reached)
    fit_departure_to_nodes<D, K>(grid, q, fp, *nodal, had, out);
  else
    fit_pressures_to_nodes<D, K>(grid, q, fp, out);
}

/// The points' pressures moved by the nodal increments between two nodal fields:
/// dP_p = sum_i N_i (P_i,end - P_i,start).
template <int D, class K>
void add_nodal_increments(const PointQuadrature<D, K>& q,
                          const std::array<std::vector<double>, 2>& start,
                          const std::array<std::vector<double>, 2>& end, FluidPoints<D>& fp) {
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    double dl = 0.0, dg = 0.0;
    for (int a = 0; a < st.n; ++a) {
      const auto i = st.node[a];
      dl += st.w[a] * (end[liquid_phase][i] - start[liquid_phase][i]);
      dg += st.w[a] * (end[gas_phase][i] - start[gas_phase][i]);
    }
    fp.liquid_pressure[p] += dl;
    fp.gas_pressure[p] += dg;
  }
}

}  // namespace unsatmpm::numerics
