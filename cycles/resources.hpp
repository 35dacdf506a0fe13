// What a case will cost before anything is allocated: the grid's nodes, the material points and
// an estimate of the memory a run holds, checked against a limit (docs/input.md, "Resource
// limits"). `check` and `run` refuse a case over the limit with the key that asks for it, before
// the grid or the points exist.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "input/case.hpp"
#include "input/input_node.hpp"

namespace unsatmpm {

struct ResourceEstimate {
  double nodes = 0.0;   // grid nodes, prod(cells + 1)
  double points = 0.0;  // material points: exact for boxes, at most for polygons
  double bytes = 0.0;   // memory a run holds [bytes], by the measured model of docs/input.md
  std::vector<double> body_points;  // per body, as `points` (overlaps not subtracted)
  int largest_body = -1;            // the body with the most points
  bool points_exact = true;         // false if a polygon's points were bounded by its bounding box
};

/// The estimate for a case run on `n_threads` threads.
ResourceEstimate estimate_resources(const Case& c, int n_threads);

/// 80 % of this machine's physical memory [bytes] (the default limit), or 8 GiB if the system
/// does not say.
double default_memory_limit();

/// "1.2 GB", "340 MB", ... (decimal units).
std::string format_bytes(double bytes);

/// "about 1.2 GB of memory (N grid nodes, M material points)".
std::string describe_resources(const ResourceEstimate& e);

/// Throws InputError at a body that holds no sample point (a box or polygon thinner than the
/// sample spacing), and if the estimate exceeds `limit_bytes`, at the key that asks for the most:
/// grid.cells when the nodes alone exceed it, else the largest body's points_per_cell. `root` is
/// the case file's document, read again only to point at the key's line.
void require_resources(const Case& c, const InputNode& root, int n_threads, double limit_bytes);

}  // namespace unsatmpm
