#include "input/input_node.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace unsatmpm {

namespace {

std::string join(const std::vector<std::string>& words, const char* separator) {
  std::string out;
  for (std::size_t i = 0; i < words.size(); ++i) out += (i ? separator : "") + words[i];
  return out;
}

// Built with append: GCC 12 warns falsely (-Wrestrict, bug 105329) on "literal" + std::string&&.
std::string in_quotes(std::string_view text) {
  std::string out(1, '\'');
  return out.append(text).append(1, '\'');
}

std::string location_of(const std::string& file, const YAML::Mark& mark) {
  return file + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

}  // namespace

std::string format_number(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  std::string text(buffer, result.ptr);
  // "1e+07" -> "1.0e+07": YAML 1.1 readers (PyYAML) need the dot to see a float.
  const auto e = text.find('e');
  if (e != std::string::npos && text.find('.') == std::string::npos) text.insert(e, ".0");
  return text;
}

// ---------------------------------------------------------------------------------------- Range

bool Range::contains(double value) const {
  const bool above = lo_open ? value > lo : value >= lo;
  const bool below = hi_open ? value < hi : value <= hi;
  return above && below;
}

std::string Range::to_string() const {
  std::string out(lo_open ? "(" : "[");
  return out.append(format_number(lo))
      .append(", ")
      .append(format_number(hi))
      .append(hi_open ? ")" : "]");
}

// ------------------------------------------------------------------------------------ InputNode

InputNode::InputNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string path,
                     YAML::Mark fallback)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)), mark_(fallback) {
  if (!node_.IsNull() && !node_.Mark().is_null()) mark_ = node_.Mark();
}

InputNode InputNode::load_file(const std::string& path) {
  // Only a regular file of bounded size is read: a device (/dev/zero), a FIFO or a directory is
  // refused at once, before any read could block or grow without end.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec) throw InputError(path + ": cannot open the file (" + ec.message() + ")");
  if (std::filesystem::is_directory(status))
    throw InputError(path + ": cannot read the file (it is a directory)");
  if (!std::filesystem::is_regular_file(status))
    throw InputError(path + ": not a regular file (a device, FIFO or socket); give a case file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path + ": cannot read the file size (" + ec.message() + ")");
  if (size > max_case_file_bytes)
    throw InputError(path + ": the file has " + std::to_string(size) +
                     " bytes, more than a case file's limit of " +
                     std::to_string(max_case_file_bytes) + " bytes (docs/input.md)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file (" + std::strerror(errno) + ")");
  std::string text(max_case_file_bytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw InputError(path + ": cannot read the file");
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > max_case_file_bytes)  // grew since the size was read
    throw InputError(path + ": the file is larger than a case file's limit of " +
                     std::to_string(max_case_file_bytes) + " bytes (docs/input.md)");
  return load_text(text, path);
}

InputNode InputNode::load_text(const std::string& text, const std::string& file_name) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(location_of(file_name, e.mark) + ": YAML syntax error: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw InputError(file_name + ": cannot parse YAML: " + e.what());
  }
  if (documents.size() > 1)
    throw InputError(location_of(file_name, documents[1].Mark()) +
                     ": expected one YAML document, found " + std::to_string(documents.size()));
  auto file = std::make_shared<const std::string>(file_name);
  return InputNode(documents.empty() ? YAML::Node() : documents[0], file, "", YAML::Mark());
}

std::optional<InputNode> InputNode::find(std::string_view key) const {
  if (!node_.IsMap()) return std::nullopt;
  for (auto it = node_.begin(); it != node_.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == key) {
      const std::string child = path_.empty() ? std::string(key) : path_ + "." + std::string(key);
      return InputNode(it->second, file_, child, it->first.Mark());
    }
  return std::nullopt;
}

std::string InputNode::location() const {
  const std::string where = location_of(*file_, mark_);
  return path_.empty() ? where : where + ": " + path_;
}

void InputNode::fail(const std::string& what) const { throw InputError(location() + ": " + what); }

void InputNode::fail_expected(const std::string& expected) const {
  fail("expected " + expected + ", got " + describe());
}

// Quoted scalars carry the non-specific tag "!": they are strings, never numbers or booleans.
// An explicit tag (!!str, !!float, !custom) is refused: a case says what a value is by its key.
bool InputNode::is_plain_scalar() const {
  require_untagged();
  return node_.IsScalar() && node_.Tag() != "!";
}

void InputNode::require_untagged() const {
  const std::string& tag = node_.Tag();
  if (!tag.empty() && tag != "?" && tag != "!")
    fail("YAML tags are not accepted (found " + tag +
         "); write the value without one (quotes make a string)");
}

std::string InputNode::describe() const {
  if (node_.IsMap()) return "a map";
  if (node_.IsSequence()) return "a sequence";
  if (node_.IsScalar() && node_.Tag() == "!")
    return "the quoted string " + in_quotes(node_.Scalar());
  if (node_.IsScalar()) return in_quotes(node_.Scalar());
  return "nothing (null)";
}

double InputNode::as_double(const Range& range) const {
  double value = 0.0;
  if (!is_plain_scalar() || !YAML::convert<double>::decode(node_, value)) fail_expected("a number");
  if (!std::isfinite(value)) fail_expected("a finite number");
  if (!range.contains(value)) fail(node_.Scalar() + " is out of range " + range.to_string());
  return value;
}

int InputNode::as_int(int lo, int hi) const {
  int value = 0;
  if (!is_plain_scalar() || !YAML::convert<int>::decode(node_, value)) fail_expected("an integer");
  if (value < lo || value > hi)
    fail(node_.Scalar() + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) +
         "]");
  return value;
}

bool InputNode::as_bool() const {
  bool value = false;
  if (!is_plain_scalar() || !YAML::convert<bool>::decode(node_, value))
    fail_expected("true or false");
  return value;
}

std::string InputNode::as_string() const {
  require_untagged();
  if (!node_.IsScalar()) fail_expected("a string");
  if (node_.Scalar().empty()) fail("expected a non-empty string");
  return node_.Scalar();
}

std::size_t InputNode::as_choice(const std::vector<std::string>& names) const {
  require_untagged();
  if (!node_.IsScalar()) fail_expected("one of " + join(names, ", "));
  const auto it = std::find(names.begin(), names.end(), node_.Scalar());
  if (it == names.end()) fail_expected("one of " + join(names, ", "));
  return static_cast<std::size_t>(it - names.begin());
}

std::vector<InputNode> InputNode::items(std::size_t min_size) const {
  if (!node_.IsSequence()) fail_expected("a sequence");
  if (node_.size() < min_size)
    fail("expected at least " + std::to_string(min_size) + " entries, got " +
         std::to_string(node_.size()));
  std::vector<InputNode> out;
  for (std::size_t i = 0; i < node_.size(); ++i)
    out.push_back(InputNode(node_[i], file_, path_ + "[" + std::to_string(i) + "]", mark_));
  return out;
}

std::vector<double> InputNode::as_vector(std::size_t n, const Range& range) const {
  if (!node_.IsSequence()) fail_expected("a list of " + std::to_string(n) + " numbers");
  if (node_.size() != n)
    fail("expected a list of " + std::to_string(n) + " numbers, got " +
         std::to_string(node_.size()));
  return as_any_vector(range);
}

std::vector<double> InputNode::as_any_vector(const Range& range, std::size_t min_size) const {
  std::vector<double> out;
  for (const InputNode& item : items(min_size)) out.push_back(item.as_double(range));
  return out;
}

std::vector<int> InputNode::as_int_vector(std::size_t n, int lo, int hi) const {
  if (!node_.IsSequence()) fail_expected("a list of " + std::to_string(n) + " integers");
  if (node_.size() != n)
    fail("expected a list of " + std::to_string(n) + " integers, got " +
         std::to_string(node_.size()));
  std::vector<int> out;
  for (const InputNode& item : items()) out.push_back(item.as_int(lo, hi));
  return out;
}

// ------------------------------------------------------------------------------------ MapReader

MapReader::MapReader(const InputNode& map, std::initializer_list<std::string_view> known_keys)
    : map_(map) {
  if (!map.node_.IsMap()) map.fail_expected("a map");
  allow(known_keys);
  // yaml-cpp keeps duplicate keys silently (lookups see the first): reject them here.
  for (auto it = map.node_.begin(); it != map.node_.end(); ++it) {
    const InputNode key(it->first, map.file_, map.path_, map.mark_);
    if (!it->first.IsScalar()) key.fail_expected("a plain key");
    Entry entry{it->first.Scalar(), it->first, it->second};
    const InputNode located(it->first, map.file_, child(entry).path(), map.mark_);
    if (const Entry* first = find(entry.key))
      located.fail("duplicate key " + in_quotes(entry.key) + " (first given at line " +
                   std::to_string(first->key_node.Mark().line + 1) + ")");
    entries_.push_back(std::move(entry));
  }
}

const MapReader::Entry* MapReader::find(std::string_view key) const {
  for (const Entry& e : entries_)
    if (e.key == key) return &e;
  return nullptr;
}

InputNode MapReader::child(const Entry& entry) const {
  const std::string path = map_.path_.empty() ? entry.key : map_.path_ + "." + entry.key;
  return InputNode(entry.value, map_.file_, path, entry.key_node.Mark());
}

void MapReader::require_declared(std::string_view key) const {
  if (std::find(known_.begin(), known_.end(), key) == known_.end())
    throw std::logic_error("input reader asks for undeclared key '" + std::string(key) + "' in " +
                           map_.location());
}

void MapReader::allow(std::initializer_list<std::string_view> keys) {
  for (const std::string_view key : keys) known_.emplace_back(key);
}

bool MapReader::has(std::string_view key) const {
  require_declared(key);
  return find(key) != nullptr;
}

InputNode MapReader::required(std::string_view key) {
  require_declared(key);
  if (const Entry* entry = find(key)) return child(*entry);
  check_unknown_keys();
  const std::string where = map_.path_.empty() ? "at top level" : "in " + map_.path_;
  map_.fail("missing required key " + in_quotes(key) + " " + where +
            "; known keys: " + known_list());
}

std::optional<InputNode> MapReader::optional(std::string_view key) {
  require_declared(key);
  if (const Entry* entry = find(key)) return child(*entry);
  return std::nullopt;
}

std::string MapReader::known_list() const { return join(known_, ", "); }

void MapReader::check_unknown_keys() const {
  for (const Entry& entry : entries_) {
    if (std::find(known_.begin(), known_.end(), entry.key) != known_.end()) continue;
    const std::string where = map_.path_.empty() ? "at top level" : "in " + map_.path_;
    const InputNode located(entry.key_node, map_.file_, child(entry).path(), map_.mark_);
    located.fail("unknown key " + in_quotes(entry.key) + " " + where +
                 "; known keys: " + known_list());
  }
}

double MapReader::required_double(std::string_view key, const Range& range) {
  return required(key).as_double(range);
}

double MapReader::optional_double(std::string_view key, double fallback, const Range& range) {
  const auto value = optional(key);
  return value ? value->as_double(range) : fallback;
}

int MapReader::required_int(std::string_view key, int lo, int hi) {
  return required(key).as_int(lo, hi);
}

bool MapReader::optional_bool(std::string_view key, bool fallback) {
  const auto value = optional(key);
  return value ? value->as_bool() : fallback;
}

std::string MapReader::required_string(std::string_view key) { return required(key).as_string(); }

}  // namespace unsatmpm
