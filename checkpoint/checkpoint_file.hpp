// The checkpoint file (docs/output.md, "Checkpoints and resume"): a run's whole state as a
// sequence of named, typed sections, written in this order and read back in the same order.
//
// Layout (all integers little-endian, as this program's machines store them; the byte-order mark
// refuses a file from a machine that differs):
//   header   16 bytes "UNSATMPM-CHKPT\0\0", u32 format version, u32 byte-order mark 0x01020304
//   sections each: u32 name length, the name, u8 element type (1 f64, 2 i64, 3 i32, 4 u8,
//            5 text), u32 components per element, u64 element count, count x components values
//   trailer  u64 length of the sections in bytes, u64 FNV-1a 64-bit hash of them,
//            8 bytes "CHKPTEND"
// A file whose version differs from checkpoint_format_version is refused with a message that says
// so; a truncated or altered file fails its length or hash check. Reading a section checks its
// name, type and components, so a state cannot be read into the wrong column.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace unsatmpm {

/// The version this program writes and reads. Bump it whenever the sections change.
inline constexpr std::uint32_t checkpoint_format_version = 11;

/// A checkpoint that cannot be read: missing, truncated, altered, of another version, or not
/// holding the section expected. The message names the file.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace checkpoint_detail {
enum class Type : std::uint8_t { f64 = 1, i64 = 2, i32 = 3, u8 = 4, text = 5 };

/// The element type of T, and how many of them one T holds: double, 64- and 32-bit integers,
/// bytes, and fixed-size aggregates of doubles (Eigen vectors, StorageMatrix).
template <class T>
constexpr Type type_of() {
  if constexpr (std::is_same_v<T, std::int64_t>)
    return Type::i64;
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return Type::i32;
  else if constexpr (std::is_same_v<T, std::uint8_t>)
    return Type::u8;
  else
    return Type::f64;
}
template <class T>
constexpr std::uint32_t components_of() {
  if constexpr (std::is_integral_v<T> || std::is_same_v<T, double>)
    return 1;
  else {
    static_assert(sizeof(T) % sizeof(double) == 0 && alignof(T) >= alignof(double) &&
                      std::is_trivially_destructible_v<T>,
                  "a checkpoint column holds doubles, integers or aggregates of doubles");
    return sizeof(T) / sizeof(double);
  }
}
}  // namespace checkpoint_detail

class CheckpointWriter {
 public:
  /// Opens `file` for writing (the caller renames it into place: writers/atomic_file.hpp);
  /// `label` names the checkpoint in messages.
  CheckpointWriter(const std::filesystem::path& file, std::string label);

  template <class T>
  void put(std::string_view name, const std::vector<T>& column) {
    section(name, checkpoint_detail::type_of<T>(), checkpoint_detail::components_of<T>(),
            column.size(), column.data(), column.size() * sizeof(T));
  }
  template <class T>
  void value(std::string_view name, const T& x) {
    section(name, checkpoint_detail::type_of<T>(), checkpoint_detail::components_of<T>(), 1, &x,
            sizeof(T));
  }
  void text(std::string_view name, std::string_view s);
  /// Writes the trailer and closes the file; throws std::runtime_error naming the file and the
  /// system's reason if anything could not be written.
  void finish();

 private:
  void section(std::string_view name, checkpoint_detail::Type type, std::uint32_t components,
               std::uint64_t count, const void* data, std::size_t bytes);
  void raw(const void* data, std::size_t bytes);

  std::ofstream out_;
  std::string label_;
  std::uint64_t length_ = 0, hash_;
};

class CheckpointReader {
 public:
  /// Opens and checks `file` (header, version, byte order, length); throws CheckpointError.
  explicit CheckpointReader(const std::filesystem::path& file);

  template <class T>
  void get(std::string_view name, std::vector<T>& column) {
    const auto count = section(name, checkpoint_detail::type_of<T>(),
                               checkpoint_detail::components_of<T>(), sizeof(T));
    column.resize(count);
    raw(column.data(), count * sizeof(T));
  }
  template <class T>
  T value(std::string_view name) {
    T x{};
    if (section(name, checkpoint_detail::type_of<T>(), checkpoint_detail::components_of<T>(),
                sizeof(T)) != 1)
      fail("section '" + std::string(name) + "' holds more than one value");
    raw(&x, sizeof(T));
    return x;
  }
  /// Reads a column that must hold `expected` elements (a state matching the case's points).
  template <class T>
  void get_sized(std::string_view name, std::vector<T>& column, std::size_t expected) {
    get(name, column);
    if (column.size() != expected)
      fail("section '" + std::string(name) + "' holds " + std::to_string(column.size()) +
           " elements where the case has " + std::to_string(expected));
  }
  std::string text(std::string_view name);
  /// Checks that every section was read and the hash matches; throws CheckpointError.
  void finish();

  [[noreturn]] void fail(const std::string& what) const;

 private:
  std::uint64_t section(std::string_view name, checkpoint_detail::Type type,
                        std::uint32_t components, std::size_t element_bytes);
  void raw(void* data, std::size_t bytes);

  std::filesystem::path file_;
  std::ifstream in_;
  std::uint64_t length_ = 0, expected_hash_ = 0, read_ = 0, hash_;
};

}  // namespace unsatmpm
