// The case reader: the `materials` and `fluids` sections. Physics parameters are checked by the
// physics factories only (one source of truth for their ranges); a ParameterError they throw is
// reported at the key of the parameter it names, angles with their value in degrees. Quantities
// without a physics type (porosity, permeability, viscosities, grain density) are checked here.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "input/case_parser_sections.hpp"
#include "physics/fluids.hpp"
#include "physics/parameter_error.hpp"
#include "physics/permeability.hpp"
#include "physics/retention.hpp"

namespace unsatmpm::case_sections {

namespace {

/// "35 deg is out of range [0, 30] deg (model: ...)" from the model's message in radians, which
/// states the range as "valid: [lo, hi] rad" (either bracket open or closed). Parsed by hand:
/// std::regex here drew GCC 12 -Wmaybe-uninitialized false positives in libstdc++ at -O1.
std::string angle_message(double degrees, const std::string& model_message) {
  const std::string rejected =
      format_number(degrees) + " deg is rejected by the model: " + model_message;
  const std::string& msg = model_message;
  const auto at = msg.find("valid: ");
  if (at == std::string::npos) return rejected;
  const std::size_t open = at + 7;
  if (open >= msg.size() || (msg[open] != '[' && msg[open] != '(')) return rejected;
  const auto comma = msg.find(", ", open + 1);
  if (comma == std::string::npos || comma == open + 1) return rejected;
  const auto close = msg.find_first_of("])", comma + 2);
  if (close == std::string::npos || close == comma + 2 || msg.compare(close + 1, 4, " rad") != 0)
    return rejected;
  const auto to_degrees = [](const std::string& radians) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.5g",
                  radians_to_degrees(std::strtod(radians.c_str(), nullptr)));
    return std::string(text);
  };
  return format_number(degrees) + " deg is out of range " + msg[open] +
         to_degrees(msg.substr(open + 1, comma - open - 1)) + ", " +
         to_degrees(msg.substr(comma + 2, close - comma - 2)) + msg[close] +
         " deg (model: " + model_message + ")";
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

/// Calls a physics factory; a ParameterError it throws is reported at the key it names.
template <class Factory>
auto create(const ParameterKeys& keys, Factory&& factory) {
  try {
    return factory();
  } catch (const physics::ParameterError& e) {
    keys.report(e);
  }
}

/// The `model` of a map whose other keys depend on it: its index in `names`. Checked before the
/// model's keys are declared, so that a missing model is not reported as an unknown other key.
std::size_t read_model(MapReader& m, const std::vector<std::string>& names) {
  if (!m.has("model")) {
    std::string list;
    for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
    m.node().fail("missing required key 'model' in " + m.node().path() + "; models: " + list);
  }
  return m.required("model").as_choice(names);
}

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

/// `mohr_coulomb` with `suction_strength` (three-phase cases): the strength of eqs. 13-14 at the
/// point's current suction. Without `tensile_strength` the cut-off is the cone's apex at every
/// suction (t' = infinity).
physics::SuctionMohrCoulomb read_suction_mohr_coulomb(MapReader& m,
                                                      const physics::LinearElastic& elastic,
                                                      ParameterKeys& keys) {
  const double cohesion = keys.read(m, "cohesion");
  const double friction = keys.read(m, "friction_angle", Unit::degrees);
  const double dilatancy = keys.read_optional(m, "dilatancy_angle", Unit::degrees).value_or(0.0);
  const double tensile =
      keys.read_optional(m, "tensile_strength").value_or(std::numeric_limits<double>::infinity());
  const auto [increase, rate, friction_increase] =
      m.required("suction_strength")
          .read_map({"cohesion_increase", "cohesion_rate", "friction_increase"}, [&](MapReader& s) {
            // friction_increase: degrees per atmosphere of suction in the file, radians per atm
            // here.
            return std::array<double, 3>{keys.read(s, "cohesion_increase"),
                                         keys.read(s, "cohesion_rate"),
                                         keys.read(s, "friction_increase", Unit::degrees)};
          });
  return create(keys, [&] {
    return physics::SuctionMohrCoulomb::create(
        elastic, physics::SuctionStrength::create(cohesion, increase, rate, friction,
                                                  friction_increase, dilatancy, tensile));
  });
}

/// A law given as `points: [[x, y], ...]`: `create` builds it from the pairs; a ParameterError
/// naming "points[k]" is reported at that point, any other at `points`.
template <class Create>
auto read_points(MapReader& m, Create&& create) {
  const InputNode node = m.required("points");
  if (!node.is_sequence()) node.fail("expected a list of [x, y] pairs, got " + node.describe());
  std::vector<std::array<double, 2>> points;
  const std::vector<InputNode> rows = node.items();
  for (const InputNode& row : rows) {
    if (!row.is_sequence() || row.size() != 2)
      row.fail("expected an [x, y] pair, got " + row.describe());
    const std::vector<InputNode> pair = row.items();
    points.push_back({pair[0].as_double(), pair[1].as_double()});
  }
  try {
    return create(points);
  } catch (const physics::ParameterError& e) {
    const std::string& p = e.parameter();
    if (p.rfind("points[", 0) == 0) {
      const std::size_t k = std::stoul(p.substr(7));
      if (k < rows.size()) rows[k].fail(e.what());
    }
    node.fail(e.what());
  }
}

physics::RetentionCurve read_retention(const InputNode& node) {
  return node.read_map({"model"}, [&](MapReader& m) -> physics::RetentionCurve {
    const std::size_t model = read_model(m, retention_names);
    ParameterKeys keys(m.node());
    if (retention_names[model] == "table") {
      m.allow({"points", "occluded_gas_scale"});
      auto r = read_points(m, [](const auto& p) { return physics::TabulatedRetention::create(p); });
      const double scale = keys.read_optional(m, "occluded_gas_scale").value_or(0.0);
      r.occluded = create(keys, [&] {
        return physics::OccludedGas::create(scale, r.table.front(), "the saturation at suction 0");
      });
      return r;
    }
    if (retention_names[model] == "linear") {
      m.allow({"a_s", "residual_saturation"});
      const double a_s = keys.read(m, "a_s");
      const double s_min = keys.read_optional(m, "residual_saturation").value_or(0.0);
      return create(keys, [&] { return physics::LinearRetention::create(a_s, s_min); });
    }
    m.allow({"p0", "lambda", "residual_saturation", "max_saturation", "occluded_gas_scale"});
    const double p0 = keys.read(m, "p0");
    const double lambda = keys.read(m, "lambda");
    const double s_min = keys.read(m, "residual_saturation");
    const double s_max = keys.read_optional(m, "max_saturation").value_or(1.0);
    const double scale = keys.read_optional(m, "occluded_gas_scale").value_or(0.0);
    return create(keys,
                  [&] { return physics::VanGenuchten::create(p0, lambda, s_min, s_max, scale); });
  });
}

physics::LiquidRelPerm read_liquid_relative_permeability(const InputNode& node) {
  return node.read_map({"model"}, [&](MapReader& m) -> physics::LiquidRelPerm {
    const std::string& model = liquid_relperm_names[read_model(m, liquid_relperm_names)];
    ParameterKeys keys(m.node());
    if (model == "table") {
      m.allow({"points"});
      return read_points(m,
                         [](const auto& p) { return physics::TabulatedRelPerm::create(p, false); });
    }
    if (model == "power") {
      m.allow({"exponent"});
      const double exponent = keys.read(m, "exponent");
      return create(keys, [&] { return physics::PowerRelPerm::create(exponent); });
    }
    if (model == "mualem_van_genuchten") {
      m.allow({"lambda"});
      const double lambda = keys.read(m, "lambda");
      return create(keys, [&] { return physics::MualemVanGenuchten::create(lambda); });
    }
    return physics::ConstantRelPerm{};
  });
}

physics::GasRelPerm read_gas_relative_permeability(const InputNode& node) {
  return node.read_map({"model"}, [&](MapReader& m) -> physics::GasRelPerm {
    const std::string& model = gas_relperm_names[read_model(m, gas_relperm_names)];
    if (model == "constant") return physics::ConstantRelPerm{};
    if (model == "table") {
      m.allow({"points"});
      return read_points(m,
                         [](const auto& p) { return physics::TabulatedRelPerm::create(p, true); });
    }
    m.allow({"exponent"});
    ParameterKeys keys(m.node());
    const double exponent = keys.read(m, "exponent");
    return create(keys, [&] { return physics::GasPowerRelPerm::create(exponent); });
  });
}

HydraulicSpec read_hydraulic(MapReader& m) {
  const double solid_density = m.required_double("solid_density", Range::open_closed(0.0, 1e5));
  const double porosity = m.required_double("porosity", Range::open(0.0, 1.0));
  const double permeability = m.required_double("intrinsic_permeability", Range::positive());
  physics::RetentionCurve retention = read_retention(m.required("retention"));
  physics::LiquidRelPerm liquid =
      read_liquid_relative_permeability(m.required("liquid_relative_permeability"));
  physics::GasRelPerm gas = read_gas_relative_permeability(m.required("gas_relative_permeability"));
  std::optional<double> maximum;
  if (const auto node = m.optional("maximum_porosity"))
    maximum = node->as_double(Range::open(porosity, 1.0));
  return {solid_density, porosity, permeability, retention, liquid, gas, maximum};
}

MaterialSpec read_material(MapReader& m, const Case& c,
                           std::vector<std::pair<std::string, int>>& names) {
  MaterialSpec material;
  const InputNode name = m.required("name");
  material.name = name.as_string();
  require_unique_name(name, material.name, "material", names);
  if (c.phases == Phases::solid) {
    material.density = m.required_double("density", Range::open_closed(0.0, 1e5));
  } else {
    material.hydraulic = read_hydraulic(m);
    // Mass of solid per unit volume of mixture: the solid's share of the mixture momentum.
    material.density = (1.0 - material.hydraulic->porosity) * material.hydraulic->solid_density;
  }
  const std::string model = model_names[m.required("model").as_choice(model_names)];
  // The model's keys are known before any is required: a missing young_modulus is then
  // reported as missing, not as an unknown cohesion.
  if (model == "mohr_coulomb") {
    m.allow({"cohesion", "friction_angle", "dilatancy_angle", "tensile_strength"});
    if (material.hydraulic) m.allow({"suction_strength"});
  }
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
    if (material.hydraulic && m.has("suction_strength")) {
      material.model = read_suction_mohr_coulomb(m, elastic, keys);
    } else {
      material.model = read_mohr_coulomb(m, elastic, keys);
    }
  }
  return material;
}

}  // namespace

std::vector<MaterialSpec> parse_materials(const InputNode& node, const Case& c) {
  if (node.is_sequence() && node.size() == 0) node.fail("at least one material is required");
  std::vector<MaterialSpec> materials;
  std::vector<std::pair<std::string, int>> names;
  const auto read = [&](MapReader& m) { return read_material(m, c, names); };
  for (const InputNode& item : node.items(1)) {
    if (c.phases == Phases::solid)
      materials.push_back(with_unknown_key_hint(
          item,
          {"solid_density", "porosity", "intrinsic_permeability", "retention",
           "liquid_relative_permeability", "gas_relative_permeability", "suction_strength",
           "maximum_porosity"},
          three_phase_hint, [&] {
            return item.read_map({"name", "density", "model", "young_modulus", "poisson_ratio"},
                                 read);
          }));
    else
      materials.push_back(with_unknown_key_hint(
          item, {"density"}, "a three-phase material gives solid_density and porosity instead",
          [&] {
            return item.read_map(
                {"name", "model", "young_modulus", "poisson_ratio", "solid_density", "porosity",
                 "intrinsic_permeability", "retention", "liquid_relative_permeability",
                 "gas_relative_permeability", "maximum_porosity"},
                read);
          }));
  }
  return materials;
}

namespace {

/// rho = rho0 exp((p - p0) / K) from {density, bulk_modulus, reference_pressure}; `viscosity`.
std::pair<physics::CompressibleFluid, double> read_compressible(MapReader& m) {
  ParameterKeys keys(m.node());
  const double density = keys.read(m, "density");
  const double bulk_modulus = keys.read(m, "bulk_modulus");
  const double reference_pressure = keys.read_optional(m, "reference_pressure").value_or(0.0);
  const double viscosity = m.required_double("viscosity", Range::positive());
  return {create(keys,
                 [&] {
                   return physics::CompressibleFluid::create(density, reference_pressure,
                                                             bulk_modulus);
                 }),
          viscosity};
}

std::pair<physics::GasLaw, double> read_gas(MapReader& m) {
  if (gas_model_names[read_model(m, gas_model_names)] == "bulk_modulus") {
    m.allow({"bulk_modulus", "reference_pressure"});
    return read_compressible(m);
  }
  ParameterKeys keys(m.node());
  const double density = keys.read(m, "density");
  const double viscosity = m.required_double("viscosity", Range::positive());
  return {create(keys, [&] { return physics::IdealGas::create(density); }), viscosity};
}

}  // namespace

FluidsSpec parse_fluids(const InputNode& node) {
  return node.read_map({"liquid", "gas"}, [&](MapReader& m) {
    const auto [liquid, liquid_viscosity] = m.required("liquid").read_map(
        {"density", "bulk_modulus", "viscosity", "reference_pressure"}, read_compressible);
    const auto [gas, gas_viscosity] =
        m.required("gas").read_map({"model", "density", "viscosity"}, read_gas);
    return FluidsSpec{liquid, liquid_viscosity, gas, gas_viscosity};
  });
}

}  // namespace unsatmpm::case_sections
