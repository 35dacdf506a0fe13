// The effective configuration's writer, shared by its two files (input/case_configuration.cpp:
// the case; input/case_configuration_materials.cpp: materials and fluids). Internal to input/.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "input/case.hpp"

namespace unsatmpm::configuration {

/// Shortest decimal degrees that convert back to exactly `radians`.
std::string degrees_text(double radians);
/// A flow sequence of numbers, each in its shortest exact form.
YAML::Emitter& operator<<(YAML::Emitter& out, const std::vector<double>& v);
/// `key: value` in the shortest exact form.
void write_number(YAML::Emitter& out, const char* key, double value);
/// `materials:` and `fluids:` of a case.
void write_materials(YAML::Emitter& out, const std::vector<MaterialSpec>& materials);
void write_fluids(YAML::Emitter& out, const FluidsSpec& fluids);

}  // namespace unsatmpm::configuration
