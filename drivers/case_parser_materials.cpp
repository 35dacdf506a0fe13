// The case reader: the `materials` section. Physics parameters are checked by the physics
// factories only (one source of truth for their ranges); a ParameterError they throw is reported
// at the key of the parameter it names, angles with their value in degrees.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "drivers/case_parser_sections.hpp"
#include "physics/parameter_error.hpp"

namespace unsatmpm::drivers::case_sections {

namespace {

/// "35 deg is out of range [0, 30] deg (model: ...)" from the model's message in radians.
std::string angle_message(double degrees, const std::string& model_message) {
  static const std::regex range(R"(valid: ([\[(])([^,]+), ([^\])]+)([\])]) rad)");
  std::smatch m;
  if (!std::regex_search(model_message, m, range))
    return format_number(degrees) + " deg is rejected by the model: " + model_message;
  const auto to_degrees = [](const std::string& radians) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.5g",
                  radians_to_degrees(std::strtod(radians.c_str(), nullptr)));
    return std::string(text);
  };
  return format_number(degrees) + " deg is out of range " + m[1].str() + to_degrees(m[2]) + ", " +
         to_degrees(m[3]) + m[4].str() + " deg (model: " + model_message + ")";
}

enum class Unit { plain, degrees };  // degrees: an angle, radians in the Case

/// Where each physics parameter came from, to put a ParameterError at the right key.
class ParameterKeys {
 public:
  explicit ParameterKeys(const InputNode& material) : material_(material) {}

  /// A number; angles are degrees in the file and returned in radians.
  double read(MapReader& m, const char* key, Unit unit = Unit::plain) {
    return value(m.required(key), key, unit);
  }
  std::optional<double> read_optional(MapReader& m, const char* key, Unit unit = Unit::plain) {
    const auto node = m.optional(key);
    if (!node) return std::nullopt;
    return value(*node, key, unit);
  }

  [[noreturn]] void report(const physics::ParameterError& e) const {
    for (const auto& [key, node, unit] : keys_) {
      if (key != e.parameter()) continue;
      if (unit == Unit::plain) node.fail(e.what());
      node.fail(angle_message(node.as_double(), e.what()));
    }
    material_.fail("the default value of " + e.parameter() + " is rejected: " + e.what());
  }

 private:
  struct Key {
    std::string name;
    InputNode node;
    Unit unit;
  };
  double value(const InputNode& node, const char* key, Unit unit) {
    keys_.push_back({key, node, unit});
    const double x = node.as_double();
    return unit == Unit::degrees ? degrees_to_radians(x) : x;
  }

  const InputNode& material_;
  std::vector<Key> keys_;
};

physics::MohrCoulomb read_mohr_coulomb(MapReader& m, const physics::LinearElastic& elastic,
                                       ParameterKeys& keys) {
  physics::MohrCoulombStrength strength{};
  strength.cohesion = keys.read(m, "cohesion");
  strength.friction_angle = keys.read(m, "friction_angle", Unit::degrees);
  strength.dilatancy_angle = keys.read_optional(m, "dilatancy_angle", Unit::degrees).value_or(0.0);
  const std::optional<double> tensile = keys.read_optional(m, "tensile_strength");
  try {
    // First without tension (always admissible) so that the default below, c / tan(phi), is
    // computed only from a valid friction angle.
    strength.tensile_strength = 0.0;
    physics::MohrCoulomb::validate(strength);
    strength.tensile_strength =
        tensile ? *tensile : strength.cohesion / std::tan(strength.friction_angle);
    return physics::MohrCoulomb::create(elastic, strength);
  } catch (const physics::ParameterError& e) {
    keys.report(e);
  }
}

MaterialSpec read_material(MapReader& m, std::vector<std::pair<std::string, int>>& names) {
  MaterialSpec material;
  const InputNode name = m.required("name");
  material.name = name.as_string();
  require_unique_name(name, material.name, "material", names);
  material.density = m.required_double("density", Range::open_closed(0.0, 1e5));
  const std::string model = model_names[m.required("model").as_choice(model_names)];
  ParameterKeys keys(m.node());
  const double young_modulus = keys.read(m, "young_modulus");
  const double poisson_ratio = keys.read(m, "poisson_ratio");
  physics::LinearElastic elastic{};
  try {
    elastic = physics::LinearElastic::create(young_modulus, poisson_ratio);
  } catch (const physics::ParameterError& e) {
    keys.report(e);
  }
  material.model = elastic;
  if (model == "mohr_coulomb") {
    m.allow({"cohesion", "friction_angle", "dilatancy_angle", "tensile_strength"});
    material.model = read_mohr_coulomb(m, elastic, keys);
  }
  return material;
}

}  // namespace

std::vector<MaterialSpec> parse_materials(const InputNode& node) {
  if (node.is_sequence() && node.size() == 0) node.fail("at least one material is required");
  std::vector<MaterialSpec> materials;
  std::vector<std::pair<std::string, int>> names;
  for (const InputNode& item : node.items(1))
    materials.push_back(
        item.read_map({"name", "density", "model", "young_modulus", "poisson_ratio"},
                      [&](MapReader& m) { return read_material(m, names); }));
  return materials;
}

}  // namespace unsatmpm::drivers::case_sections
