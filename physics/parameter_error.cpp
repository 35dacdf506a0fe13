#include "physics/parameter_error.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace unsatmpm::physics {

std::string number_text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

namespace {
std::string describe(const char* parameter, double value, double lo, double hi, const char* unit,
                     bool open) {
  // A dimensionless parameter's unit "-" is left out of the sentence.
  const std::string u = std::string(unit) == "-" ? "" : std::string(" ") + unit;
  std::ostringstream os;
  os << parameter << " = " << value << u << " is out of range; valid: " << (open ? "(" : "[") << lo
     << ", " << hi << (open ? ")" : "]") << u;
  return os.str();
}
}  // namespace

void require_in_range(const char* parameter, double value, double lo, double hi, const char* unit) {
  if (!std::isfinite(value) || value < lo || value > hi)
    throw ParameterError(parameter, describe(parameter, value, lo, hi, unit, false));
}

void require_in_open_range(const char* parameter, double value, double lo, double hi,
                           const char* unit) {
  if (!std::isfinite(value) || value <= lo || value >= hi)
    throw ParameterError(parameter, describe(parameter, value, lo, hi, unit, true));
}

}  // namespace unsatmpm::physics
