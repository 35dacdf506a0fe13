// Reading a case (input/case.hpp) from YAML, and writing it back as its effective configuration.
//
// The schema and every key's type, unit, default and range are documented in docs/input.md. The
// reader is strict: unknown or duplicate keys, wrong types, non-finite numbers, out-of-range
// values and inconsistent sections (vector lengths, bodies outside the grid, boundary planes off
// the grid node planes, unknown material names, ...) throw InputError with
// "FILE:LINE:COLUMN: KEY.PATH: what is wrong". Physics parameters are validated by the physics
// factories (LinearElastic::create, MohrCoulomb::create); their ParameterError is reported at
// the key of the offending parameter.
#pragma once

#include <string>

#include "input/case.hpp"
#include "input/input_node.hpp"

namespace unsatmpm {

/// Parses and validates a case file. Throws InputError (also for a missing or unreadable file).
Case parse_case_file(const std::string& path);

/// Parses and validates case text; `file_name` is used in messages and stored in Case::file.
Case parse_case_text(const std::string& text, const std::string& file_name);

/// The full effective case as YAML, defaults included, angles in degrees, numbers written so
/// that they read back exactly: parse_case_text(effective_configuration(c), ...) equals c.
std::string effective_configuration(const Case& c);

}  // namespace unsatmpm
