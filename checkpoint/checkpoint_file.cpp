#include "checkpoint/checkpoint_file.hpp"

#include <array>
#include <cerrno>
#include <cstring>
#include <system_error>

namespace unsatmpm {

namespace {

using checkpoint_detail::Type;

constexpr std::array<char, 16> magic{'U', 'N', 'S', 'A', 'T', 'M', 'P',  'M',
                                     '-', 'C', 'H', 'K', 'P', 'T', '\0', '\0'};
constexpr std::array<char, 8> end_magic{'C', 'H', 'K', 'P', 'T', 'E', 'N', 'D'};
constexpr std::uint32_t byte_order_mark = 0x01020304;
constexpr std::uint64_t fnv_offset = 14695981039346656037ull, fnv_prime = 1099511628211ull;
constexpr std::size_t header_bytes = 16 + 4 + 4, trailer_bytes = 8 + 8 + 8;
/// Longest section name read (a longer one is a damaged file, not a large allocation).
constexpr std::uint32_t max_name_length = 256;

void fnv1a(std::uint64_t& hash, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * fnv_prime;
}

const char* type_name(Type t) {
  switch (t) {
    case Type::f64:
      return "f64";
    case Type::i64:
      return "i64";
    case Type::i32:
      return "i32";
    case Type::u8:
      return "u8";
    case Type::text:
      return "text";
  }
  return "unknown";
}

}  // namespace

CheckpointWriter::CheckpointWriter(const std::filesystem::path& file, std::string label)
    : out_(file, std::ios::binary | std::ios::trunc), label_(std::move(label)), hash_(fnv_offset) {
  if (!out_)
    throw std::runtime_error("cannot write " + label_ + ": " +
                             std::generic_category().message(errno));
  out_.write(magic.data(), magic.size());
  out_.write(reinterpret_cast<const char*>(&checkpoint_format_version), 4);
  out_.write(reinterpret_cast<const char*>(&byte_order_mark), 4);
}

void CheckpointWriter::raw(const void* data, std::size_t bytes) {
  out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  fnv1a(hash_, data, bytes);
  length_ += bytes;
}

void CheckpointWriter::section(std::string_view name, Type type, std::uint32_t components,
                               std::uint64_t count, const void* data, std::size_t bytes) {
  const auto name_length = static_cast<std::uint32_t>(name.size());
  const auto code = static_cast<std::uint8_t>(type);
  raw(&name_length, 4);
  raw(name.data(), name.size());
  raw(&code, 1);
  raw(&components, 4);
  raw(&count, 8);
  if (bytes > 0) raw(data, bytes);
}

void CheckpointWriter::text(std::string_view name, std::string_view s) {
  section(name, Type::text, 1, s.size(), s.data(), s.size());
}

void CheckpointWriter::finish() {
  out_.write(reinterpret_cast<const char*>(&length_), 8);
  out_.write(reinterpret_cast<const char*>(&hash_), 8);
  out_.write(end_magic.data(), end_magic.size());
  if (out_) out_.close();
  if (!out_)
    throw std::runtime_error("cannot write " + label_ + ": " +
                             std::generic_category().message(errno));
}

CheckpointReader::CheckpointReader(const std::filesystem::path& file)
    : file_(file), in_(file, std::ios::binary), hash_(fnv_offset) {
  if (!in_) fail(std::string("cannot open it: ") + std::strerror(errno));
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec || size < header_bytes + trailer_bytes) fail("too short to be a checkpoint");
  std::array<char, 16> head{};
  std::uint32_t version = 0, mark = 0;
  in_.read(head.data(), head.size());
  in_.read(reinterpret_cast<char*>(&version), 4);
  in_.read(reinterpret_cast<char*>(&mark), 4);
  if (!in_ || head != magic) fail("not a checkpoint written by unsatmpm");
  if (mark != byte_order_mark) fail("written on a machine of another byte order");
  if (version != checkpoint_format_version)
    fail("checkpoint format version " + std::to_string(version) + ", but this unsatmpm reads " +
         "version " + std::to_string(checkpoint_format_version) +
         " only; run the case again from the start");
  in_.seekg(static_cast<std::streamoff>(size - trailer_bytes));
  std::array<char, 8> tail{};
  in_.read(reinterpret_cast<char*>(&length_), 8);
  in_.read(reinterpret_cast<char*>(&expected_hash_), 8);
  in_.read(tail.data(), tail.size());
  if (!in_ || tail != end_magic || length_ != size - header_bytes - trailer_bytes)
    fail("truncated or damaged (its length does not match its trailer)");
  in_.seekg(static_cast<std::streamoff>(header_bytes));
}

void CheckpointReader::fail(const std::string& what) const {
  throw CheckpointError("checkpoint '" + file_.string() + "': " + what);
}

void CheckpointReader::raw(void* data, std::size_t bytes) {
  if (bytes > length_ - read_) fail("truncated: a section runs past the end of the data");
  in_.read(static_cast<char*>(data), static_cast<std::streamsize>(bytes));
  if (!in_) fail(std::string("read error: ") + std::strerror(errno));
  fnv1a(hash_, data, bytes);
  read_ += bytes;
}

std::uint64_t CheckpointReader::section(std::string_view name, Type type, std::uint32_t components,
                                        std::size_t element_bytes) {
  std::uint32_t name_length = 0, stored_components = 0;
  std::uint8_t code = 0;
  std::uint64_t count = 0;
  raw(&name_length, 4);
  if (name_length > max_name_length)
    fail("damaged: a section name of " + std::to_string(name_length) + " bytes");
  std::string stored(name_length, '\0');
  raw(stored.data(), name_length);
  raw(&code, 1);
  raw(&stored_components, 4);
  raw(&count, 8);
  if (stored != name)
    fail("expected section '" + std::string(name) + "', found '" + stored +
         "' (a checkpoint of another cycle or dimension)");
  if (code != static_cast<std::uint8_t>(type) || stored_components != components)
    fail("section '" + stored + "' holds " + type_name(static_cast<Type>(code)) + " x " +
         std::to_string(stored_components) + ", expected " + type_name(type) + " x " +
         std::to_string(components));
  if (element_bytes > 0 && count > (length_ - read_) / element_bytes)
    fail("truncated: section '" + stored + "' claims more data than the file holds");
  return count;
}

std::string CheckpointReader::text(std::string_view name) {
  const auto count = section(name, Type::text, 1, 1);
  std::string s(count, '\0');
  raw(s.data(), count);
  return s;
}

void CheckpointReader::finish() {
  if (read_ != length_)
    fail(std::to_string(length_ - read_) + " bytes left unread (a checkpoint of another build)");
  if (hash_ != expected_hash_) fail("damaged: its contents do not match their hash");
}

}  // namespace unsatmpm
