#include "writers/output_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "writers/atomic_file.hpp"

namespace unsatmpm {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view manifest_header = "# unsatmpm output manifest 1";

/// `stem` followed by digits or "last_good", then `extension`.
bool is_series_name(std::string_view name, std::string_view stem, std::string_view extension) {
  if (!name.starts_with(stem) || !name.ends_with(extension)) return false;
  name.remove_prefix(stem.size());
  name.remove_suffix(extension.size());
  if (name == "last_good") return true;
  return !name.empty() &&
         std::all_of(name.begin(), name.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
}

/// The names a manifest lists; throws when the file is not a manifest this program wrote.
std::set<std::string> read_manifest(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line) || line != manifest_header)
    throw std::runtime_error(fmt::format(
        "{} is not a manifest written by unsatmpm; nothing was deleted", quoted_path(file)));
  std::set<std::string> names;
  while (std::getline(in, line))
    if (is_output_file_name(line)) names.insert(line);
  return names;
}

/// True when `inner` is `outer` or lies inside it (both absolute and canonical).
bool contains(const fs::path& outer, const fs::path& inner) {
  return std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end()).first == outer.end();
}

/// The entries of an existing folder that an earlier run wrote (to delete) and the foreign ones.
struct FolderContents {
  std::vector<fs::path> ours;
  std::vector<std::string> foreign;
};

FolderContents classify(const fs::path& dir) {
  const fs::path manifest = dir / OutputFolder::manifest_name;
  std::set<std::string> listed;
  if (fs::is_regular_file(fs::symlink_status(manifest))) listed = read_manifest(manifest);
  FolderContents contents;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    const bool regular = fs::is_regular_file(entry.symlink_status());
    std::string_view base = name;
    if (base.ends_with(".tmp")) base.remove_suffix(4);  // left by a run killed mid-write
    const bool ours =
        regular && (name == OutputFolder::manifest_name || name == OutputFolder::lock_name ||
                    listed.contains(std::string(base)));
    if (!ours)
      contents.foreign.push_back(name);
    else if (name != OutputFolder::lock_name)
      contents.ours.push_back(entry.path());
  }
  std::sort(contents.foreign.begin(), contents.foreign.end());
  return contents;
}

std::string list_some(const std::vector<std::string>& names) {
  std::string out;
  const std::size_t shown = std::min<std::size_t>(names.size(), 5);
  for (std::size_t i = 0; i < shown; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > shown) out += fmt::format(" and {} more", names.size() - shown);
  return out;
}

}  // namespace

bool is_output_file_name(std::string_view name) {
  static constexpr std::string_view fixed[] = {"points.pvd",       "grid.pvd",
                                               "globals.csv",      "control_points.csv",
                                               "conservation.csv", "effective_case.yaml",
                                               "run_summary.json", "checkpoint.bin"};
  return std::find(std::begin(fixed), std::end(fixed), name) != std::end(fixed) ||
         is_series_name(name, "points_", ".vtu") || is_series_name(name, "grid_", ".vtu");
}

OutputFolder::OutputFolder(fs::path dir, Claim claim) : dir_(std::move(dir)) {
  const auto status = fs::status(dir_);  // follows a symbolic link
  if (fs::is_symlink(fs::symlink_status(dir_)) && !fs::exists(status))
    throw std::runtime_error(
        fmt::format("output folder {} is a symbolic link to nothing", quoted_path(dir_)));
  FolderContents contents;
  if (fs::exists(status)) {
    if (!fs::is_directory(status))
      throw std::runtime_error(
          fmt::format("output path {} exists and is not a folder", quoted_path(dir_)));
    if (contains(fs::canonical(dir_), fs::canonical(fs::current_path())))
      throw std::runtime_error(fmt::format(
          "output folder {} is the current folder or contains it; give the run a folder of its "
          "own with --output",
          quoted_path(dir_)));
    contents = classify(dir_);
    if (!contents.foreign.empty())
      throw std::runtime_error(fmt::format(
          "output folder {} holds files that no unsatmpm run listed as its own ({}); nothing was "
          "deleted; choose another folder with --output (a folder written by an unsatmpm version "
          "without {} must be emptied by hand)",
          quoted_path(dir_), list_some(contents.foreign), manifest_name));
  } else if (claim == Claim::resume) {
    throw std::runtime_error(fmt::format("{} is not a folder", quoted_path(dir_)));
  } else {
    fs::create_directories(dir_);
  }
  if (claim == Claim::resume) {
    const fs::path manifest = dir_ / manifest_name;
    if (!fs::is_regular_file(fs::symlink_status(manifest)) ||
        !(listed_ = read_manifest(manifest)).contains("checkpoint.bin"))
      throw std::runtime_error(fmt::format(
          "{} holds no checkpoint of an unsatmpm run (its manifest does not list checkpoint.bin)",
          quoted_path(dir_)));
  }
  lock();
  try {
    if (claim == Claim::resume) {  // keep the run's files; drop its unfinished writes
      for (const fs::path& file : contents.ours)
        if (file.extension() == ".tmp") fs::remove(file);
      return;
    }
    for (const fs::path& file : contents.ours) fs::remove(file);
    std::ofstream manifest(dir_ / manifest_name, std::ios::trunc);
    manifest << manifest_header << '\n';
    if (!manifest.flush())
      throw std::runtime_error(fmt::format("cannot write {}: {}", quoted_path(dir_ / manifest_name),
                                           std::strerror(errno)));
  } catch (...) {
    unlock();
    throw;
  }
}

void OutputFolder::lock() {
  const fs::path file = dir_ / lock_name;
  const bool existed = fs::exists(fs::symlink_status(file));
  lock_fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (lock_fd_ < 0)
    throw std::runtime_error(
        fmt::format("cannot create {}: {}", quoted_path(file), std::strerror(errno)));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    char pid[32] = {};
    const auto n = ::read(lock_fd_, pid, sizeof(pid) - 1);
    ::close(lock_fd_);
    lock_fd_ = -1;
    if (error == EWOULDBLOCK)
      throw std::runtime_error(fmt::format(
          "output folder {} is in use by another unsatmpm run (pid {}); nothing was "
          "deleted",
          quoted_path(dir_), n > 0 ? std::string(pid, static_cast<std::size_t>(n)) : "?"));
    throw std::runtime_error(
        fmt::format("cannot lock {}: {}", quoted_path(file), std::strerror(error)));
  }
  stale_lock_ = existed;
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(lock_fd_, 0) != 0 ||
      ::pwrite(lock_fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    const std::string why = std::strerror(errno);
    unlock();  // the constructor has not finished: no destructor will release it
    throw std::runtime_error(fmt::format("cannot write {}: {}", quoted_path(file), why));
  }
}

OutputFolder::~OutputFolder() { unlock(); }

void OutputFolder::unlock() {
  if (lock_fd_ < 0) return;
  std::error_code ignored;
  fs::remove(dir_ / lock_name, ignored);  // while still holding the lock
  ::close(lock_fd_);
  lock_fd_ = -1;
}

fs::path OutputFolder::file(const std::string& name) {
  if (!is_output_file_name(name))
    throw std::logic_error("unsatmpm writes no output file named '" + name + "'");
  if (!listed_.contains(name)) {
    append_to_manifest(name);
    listed_.insert(name);
  }
  return dir_ / name;
}

void OutputFolder::append_to_manifest(const std::string& name) const {
  std::ofstream manifest(dir_ / manifest_name, std::ios::app);
  manifest << name << '\n';
  if (!manifest.flush())
    throw std::runtime_error(fmt::format("cannot write {}: {}", quoted_path(dir_ / manifest_name),
                                         std::strerror(errno)));
}

}  // namespace unsatmpm
