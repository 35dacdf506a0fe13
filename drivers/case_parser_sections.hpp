// Internal to the case parser: the readers of its sections, shared by case_parser*.cpp and
// case_configuration.cpp (the writer). Not part of the drivers' interface.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "drivers/case.hpp"
#include "drivers/input_node.hpp"

namespace unsatmpm::drivers::case_sections {

// Names of the enumerations as written in the file (the writer uses the same tables).
extern const std::vector<std::pair<std::string, ShapeFunctionKind>> shape_function_names;
extern const std::vector<std::pair<std::string, MechanicalCondition>> mechanical_names;
extern const std::vector<std::string> axis_names;   // x, y, z
extern const std::vector<std::string> model_names;  // linear_elastic, mohr_coulomb (variant order)

/// Angles are degrees in the file and radians in a Case; these two are the only conversions.
double degrees_to_radians(double degrees);
double radians_to_degrees(double radians);

/// A list of `c.dimension` finite numbers (the message states the dimension).
std::vector<double> read_vector(const InputNode& node, int dimension,
                                const Range& range = Range::any());
/// An axis name x | y | z, restricted to the case's dimension; returns 0, 1 or 2.
int read_axis(const InputNode& node, int dimension);
/// Grid spacing along an axis and the tolerance (1e-9 spacing) used for "on the grid" tests.
double grid_spacing(const GridSpec& grid, int axis);
/// Fails at `where` unless x (c.dimension entries) lies in the grid box (within the tolerance).
void require_inside_grid(const InputNode& where, const std::vector<double>& x, const Case& c);
/// Fails at `where` if `name` repeats one of `seen` (kind: "material", "body", ...), then adds it.
void require_unique_name(const InputNode& where, const std::string& name, const char* kind,
                         std::vector<std::pair<std::string, int>>& seen);

/// Sections that need the already-parsed part of the case (dimension, grid, materials).
std::vector<MaterialSpec> parse_materials(const InputNode& node);
std::vector<BodySpec> parse_bodies(const InputNode& node, const Case& c);
std::vector<BoundarySpec> parse_boundaries(const InputNode& node, const Case& c);

}  // namespace unsatmpm::drivers::case_sections
