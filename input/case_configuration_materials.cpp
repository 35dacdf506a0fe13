// The effective configuration's materials and fluids (input/configuration_writer.hpp): each law
// written as `{model: ..., parameters}` in the input schema, numbers in their shortest exact form.
#include <yaml-cpp/yaml.h>

#include <variant>
#include <vector>

#include "input/case_parser_sections.hpp"
#include "input/configuration_writer.hpp"

namespace unsatmpm::configuration {

namespace {

using namespace case_sections;

void write_model(YAML::Emitter& out, const physics::LinearElastic& model) {
  out << YAML::Key << "model" << YAML::Value << "linear_elastic";
  out << YAML::Key << "young_modulus" << YAML::Value << format_number(model.young_modulus);
  out << YAML::Key << "poisson_ratio" << YAML::Value << format_number(model.poisson_ratio);
}

void write_model(YAML::Emitter& out, const physics::MohrCoulomb& model) {
  out << YAML::Key << "model" << YAML::Value << "mohr_coulomb";
  out << YAML::Key << "young_modulus" << YAML::Value << format_number(model.elastic.young_modulus);
  out << YAML::Key << "poisson_ratio" << YAML::Value << format_number(model.elastic.poisson_ratio);
  const physics::MohrCoulombStrength& s = model.strength;
  out << YAML::Key << "cohesion" << YAML::Value << format_number(s.cohesion);
  out << YAML::Key << "friction_angle" << YAML::Value << degrees_text(s.friction_angle);
  out << YAML::Key << "dilatancy_angle" << YAML::Value << degrees_text(s.dilatancy_angle);
  out << YAML::Key << "tensile_strength" << YAML::Value << format_number(s.tensile_strength);
}

void write_model(YAML::Emitter& out, const physics::SuctionMohrCoulomb& model) {
  const physics::SuctionStrength& s = model.strength;
  out << YAML::Key << "model" << YAML::Value << "mohr_coulomb";
  out << YAML::Key << "young_modulus" << YAML::Value
      << format_number(model.elastic().young_modulus);
  out << YAML::Key << "poisson_ratio" << YAML::Value
      << format_number(model.elastic().poisson_ratio);
  out << YAML::Key << "cohesion" << YAML::Value << format_number(s.cohesion);
  out << YAML::Key << "friction_angle" << YAML::Value << degrees_text(s.friction_angle);
  out << YAML::Key << "dilatancy_angle" << YAML::Value << degrees_text(s.dilatancy_angle);
  // Infinite t' (the default: the cone's apex at every suction) is written by leaving it out.
  if (std::isfinite(s.tensile_strength))
    out << YAML::Key << "tensile_strength" << YAML::Value << format_number(s.tensile_strength);
  out << YAML::Key << "suction_strength" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "cohesion_increase" << YAML::Value << format_number(s.cohesion_increase);
  out << YAML::Key << "cohesion_rate" << YAML::Value << format_number(s.cohesion_rate);
  out << YAML::Key << "friction_increase" << YAML::Value << degrees_text(s.friction_increase);
  out << YAML::EndMap;
}

void write_law(YAML::Emitter& out, const physics::LinearRetention& r) {
  out << YAML::Key << "model" << YAML::Value << "linear";
  write_number(out, "a_s", r.a_s);
  write_number(out, "residual_saturation", r.s_min);
}
void write_law(YAML::Emitter& out, const physics::VanGenuchten& r) {
  out << YAML::Key << "model" << YAML::Value << "van_genuchten";
  write_number(out, "p0", r.p0);
  write_number(out, "lambda", r.lambda);
  write_number(out, "residual_saturation", r.s_min);
  write_number(out, "max_saturation", r.s_max);
  write_number(out, "occluded_gas_scale", r.occluded.scale);
}
void write_law(YAML::Emitter& out, const physics::ConstantRelPerm&) {
  out << YAML::Key << "model" << YAML::Value << "constant";
}
void write_law(YAML::Emitter& out, const physics::PowerRelPerm& k) {
  out << YAML::Key << "model" << YAML::Value << "power";
  write_number(out, "exponent", k.exponent);
}
void write_law(YAML::Emitter& out, const physics::GasPowerRelPerm& k) {
  out << YAML::Key << "model" << YAML::Value << "power";
  write_number(out, "exponent", k.exponent);
}
void write_law(YAML::Emitter& out, const physics::MualemVanGenuchten& k) {
  out << YAML::Key << "model" << YAML::Value << "mualem_van_genuchten";
  write_number(out, "lambda", k.lambda);
}

void write_points(YAML::Emitter& out, const physics::MonotoneTable& t) {
  out << YAML::Key << "model" << YAML::Value << "table";
  out << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
  for (std::size_t k = 0; k < t.xs().size(); ++k) out << std::vector<double>{t.xs()[k], t.ys()[k]};
  out << YAML::EndSeq;
}
void write_law(YAML::Emitter& out, const physics::TabulatedRetention& r) {
  write_points(out, r.table);
  write_number(out, "occluded_gas_scale", r.occluded.scale);
}
void write_law(YAML::Emitter& out, const physics::TabulatedRelPerm& k) {
  write_points(out, k.table);
}

/// `key: {model: ..., parameters}` for a law held in a std::variant.
template <class Variant>
void write_law(YAML::Emitter& out, const char* key, const Variant& law) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
  std::visit([&](const auto& alternative) { write_law(out, alternative); }, law);
  out << YAML::EndMap;
}

void write_hydraulic(YAML::Emitter& out, const HydraulicSpec& h) {
  write_number(out, "solid_density", h.solid_density);
  write_number(out, "porosity", h.porosity);
  write_number(out, "intrinsic_permeability", h.intrinsic_permeability);
  write_law(out, "retention", h.retention);
  write_law(out, "liquid_relative_permeability", h.liquid_relative_permeability);
  write_law(out, "gas_relative_permeability", h.gas_relative_permeability);
  if (h.maximum_porosity) write_number(out, "maximum_porosity", *h.maximum_porosity);
}

void write_compressible(YAML::Emitter& out, const physics::CompressibleFluid& fluid) {
  write_number(out, "density", fluid.reference_density);
  write_number(out, "bulk_modulus", fluid.bulk_modulus);
  write_number(out, "reference_pressure", fluid.reference_pressure);
}

}  // namespace

void write_materials(YAML::Emitter& out, const std::vector<MaterialSpec>& materials) {
  out << YAML::Key << "materials" << YAML::Value << YAML::BeginSeq;
  for (const MaterialSpec& m : materials) {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << m.name;
    if (!m.hydraulic) write_number(out, "density", m.density);
    std::visit([&](const auto& model) { write_model(out, model); }, m.model);
    if (m.hydraulic) write_hydraulic(out, *m.hydraulic);  // density = (1 - n) rho_s follows
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

void write_fluids(YAML::Emitter& out, const FluidsSpec& f) {
  out << YAML::Key << "fluids" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "liquid" << YAML::Value << YAML::Flow << YAML::BeginMap;
  write_compressible(out, f.liquid);
  write_number(out, "viscosity", f.liquid_viscosity);
  out << YAML::EndMap;
  out << YAML::Key << "gas" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "model" << YAML::Value << gas_model_names[f.gas.index()];
  if (const auto* compressible = std::get_if<physics::CompressibleFluid>(&f.gas))
    write_compressible(out, *compressible);
  else
    write_number(out, "density", std::get<physics::IdealGas>(f.gas).reference_density);
  write_number(out, "viscosity", f.gas_viscosity);
  out << YAML::EndMap << YAML::EndMap;
}

}  // namespace unsatmpm::configuration
