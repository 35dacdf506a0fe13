// Strict, typed access to a YAML input file (yaml-cpp underneath).
//
// Every InputNode knows its file and its key path (e.g. `materials[1].young_modulus`), so any
// error can say where it is: all errors throw InputError with the message
//   FILE:LINE:COLUMN: KEY.PATH: what is wrong
// (1-based line and column). Numbers must be finite; ranges are checked where they are read.
//
// Maps are read only through InputNode::read_map(known_keys, reader): it rejects duplicate keys
// up front, and after the reader returns it rejects every key that is not in `known_keys` (the
// message lists the known keys). The unknown-key check therefore cannot be forgotten.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace unsatmpm {

/// The one exception type of the input layer; what() is "FILE:LINE:COLUMN: KEY.PATH: message".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Shortest decimal text that reads back to exactly `value` (e.g. 0.1, 1.0e+07, -9.81).
std::string format_number(double value);

/// An interval of admissible values; each bound closed or open, possibly infinite.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = true, hi_open = true;

  static Range any() { return {}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }      // [lo, hi]
  static Range open(double lo, double hi) { return {lo, hi, true, true}; }          // (lo, hi)
  static Range closed_open(double lo, double hi) { return {lo, hi, false, true}; }  // [lo, hi)
  static Range open_closed(double lo, double hi) { return {lo, hi, true, false}; }  // (lo, hi]
  static Range positive() { return open(0.0, std::numeric_limits<double>::infinity()); }
  static Range non_negative() { return closed_open(0.0, std::numeric_limits<double>::infinity()); }

  bool contains(double value) const;
  std::string to_string() const;  // e.g. "[0, 1)", "(0, inf)"
};

class MapReader;

/// The largest case file read [bytes] (docs/input.md): a case is a few kilobytes, a long
/// rainfall or load table a few hundred; a file beyond this is refused before it is read.
inline constexpr std::uintmax_t max_case_file_bytes = 4u << 20;

class InputNode {
 public:
  /// Reads and parses a file; a missing file or a YAML syntax error throws InputError.
  static InputNode load_file(const std::string& path);
  /// Parses text as if read from `file_name` (used in messages). Exactly one YAML document.
  static InputNode load_text(const std::string& text, const std::string& file_name);

  const std::string& file() const { return *file_; }
  const std::string& path() const { return path_; }  // "" for the document root
  int line() const { return mark_.line + 1; }        // 1-based
  int column() const { return mark_.column + 1; }    // 1-based
  /// "FILE:LINE:COLUMN: KEY.PATH" (no path for the root).
  std::string location() const;
  /// Throws InputError "location(): what".
  [[noreturn]] void fail(const std::string& what) const;

  /// The value of `key` in a map, read without checks (for pointing at a key in a message after
  /// parsing); nothing if this is not a map or has no such key.
  std::optional<InputNode> find(std::string_view key) const;

  bool is_null() const { return node_.IsNull(); }
  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  std::size_t size() const { return node_.IsSequence() || node_.IsMap() ? node_.size() : 0; }
  /// How the node looks, for messages: "'abc'", "a map", "a sequence", "nothing (null)".
  std::string describe() const;

  double as_double(const Range& range = Range::any()) const;  // finite, within range
  int as_int(int lo, int hi) const;                           // within [lo, hi]
  bool as_bool() const;                                       // true | false
  std::string as_string() const;                              // non-empty scalar
  /// Index of the node's text in `names`; the error lists the names.
  std::size_t as_choice(const std::vector<std::string>& names) const;
  template <class E>
  E as_enum(const std::vector<std::pair<std::string, E>>& names) const;

  /// Elements of a sequence, with paths `path[i]`. `min_size` is checked.
  std::vector<InputNode> items(std::size_t min_size = 0) const;
  /// A list of exactly `n` numbers, each within range.
  std::vector<double> as_vector(std::size_t n, const Range& range = Range::any()) const;
  /// A list of any length (>= min_size) of numbers, each within range.
  std::vector<double> as_any_vector(const Range& range = Range::any(),
                                    std::size_t min_size = 0) const;
  /// A list of exactly `n` integers, each within [lo, hi].
  std::vector<int> as_int_vector(std::size_t n, int lo, int hi) const;

  /// Reads this node as a map: `read(MapReader&)` pulls the keys it needs, then every key not in
  /// `known_keys` (plus those added with MapReader::allow) is an error. Returns what `read`
  /// returns.
  template <class F>
  auto read_map(std::initializer_list<std::string_view> known_keys, F&& read) const;

 private:
  friend class MapReader;
  InputNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string path,
            YAML::Mark fallback);
  [[noreturn]] void fail_expected(const std::string& expected) const;
  bool is_plain_scalar() const;
  /// Throws InputError if the node carries an explicit YAML tag (!!str, !!float, !x).
  void require_untagged() const;

  YAML::Node node_;
  std::shared_ptr<const std::string> file_;
  std::string path_;
  YAML::Mark mark_;  // of the value; of its key when the value is null (yaml-cpp marks those badly)
};

/// The keys of one map, handed out by InputNode::read_map. Keys must be declared as known.
class MapReader {
 public:
  MapReader(const MapReader&) = delete;
  MapReader& operator=(const MapReader&) = delete;

  const InputNode& node() const { return map_; }  // the map itself
  bool has(std::string_view key) const;
  /// The value of a key that must be present; if absent, unknown keys are reported first (one is
  /// likely the misspelt key), then the missing key at the line of the map.
  InputNode required(std::string_view key);
  std::optional<InputNode> optional(std::string_view key);
  /// Declares more known keys once a discriminating key (e.g. `model`) has been read.
  void allow(std::initializer_list<std::string_view> keys);

  // Shorthands for scalar keys.
  double required_double(std::string_view key, const Range& range = Range::any());
  double optional_double(std::string_view key, double fallback, const Range& range = Range::any());
  int required_int(std::string_view key, int lo, int hi);
  bool optional_bool(std::string_view key, bool fallback);
  std::string required_string(std::string_view key);

 private:
  friend class InputNode;
  struct Entry {
    std::string key;
    YAML::Node key_node, value;
  };
  MapReader(const InputNode& map, std::initializer_list<std::string_view> known_keys);
  const Entry* find(std::string_view key) const;
  InputNode child(const Entry& entry) const;
  void require_declared(std::string_view key) const;
  void check_unknown_keys() const;
  std::string known_list() const;

  InputNode map_;
  std::vector<Entry> entries_;
  std::vector<std::string> known_;
};

template <class E>
E InputNode::as_enum(const std::vector<std::pair<std::string, E>>& names) const {
  std::vector<std::string> text;
  for (const auto& [name, value] : names) text.push_back(name);
  return names[as_choice(text)].second;
}

template <class F>
auto InputNode::read_map(std::initializer_list<std::string_view> known_keys, F&& read) const {
  MapReader reader(*this, known_keys);
  if constexpr (std::is_void_v<std::invoke_result_t<F, MapReader&>>) {
    read(reader);
    reader.check_unknown_keys();
  } else {
    auto result = read(reader);
    reader.check_unknown_keys();
    return result;
  }
}

}  // namespace unsatmpm
