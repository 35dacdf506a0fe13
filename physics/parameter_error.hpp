// The one exception type that physics factories throw for an invalid parameter.
//
// `parameter` is the model's own parameter name (e.g. "poisson_ratio"); the input layer, which
// knows the file, line and key path, prefixes them. Physics never sees YAML.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace unsatmpm::physics {

class ParameterError : public std::invalid_argument {
 public:
  ParameterError(std::string parameter, const std::string& message)
      : std::invalid_argument(message), parameter_(std::move(parameter)) {}
  const std::string& parameter() const { return parameter_; }

 private:
  std::string parameter_;
};

/// A number for a message: the shortest of its 6-significant-digit forms ("100000", "0.9").
std::string number_text(double value);

/// Throws ParameterError unless lo <= value <= hi (and value is finite). `what` states the range.
void require_in_range(const char* parameter, double value, double lo, double hi, const char* unit);
/// Throws ParameterError unless lo < value < hi (open bounds) and finite.
void require_in_open_range(const char* parameter, double value, double lo, double hi,
                           const char* unit);

}  // namespace unsatmpm::physics
