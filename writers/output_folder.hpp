// The output folder of one run, claimed so that nothing of the user's is ever deleted.
//
// Rules (docs/output.md, "The output folder"):
//   - a run deletes only regular files that an earlier run listed in the folder's manifest
//     (unsatmpm_manifest.txt) and whose names are output names of this program; never a folder,
//     never a file it did not write;
//   - a folder holding anything else (a planted run_summary.json included) is refused whole;
//   - the folder is locked for the run's duration (flock on unsatmpm.lock): a second run into a
//     folder that a live run holds is refused; a lock left by a run that died is reported;
//   - the current folder, or a folder containing it, is refused;
//   - a symbolic link to a folder is followed (the link stays), a dangling one is refused;
//   - a resumed run (unsatmpm resume) claims the folder of the run it continues: the same checks
//     and lock, but it keeps the files listed and deletes only the temporary files of writes the
//     interrupted run did not finish.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <string_view>

namespace unsatmpm {

/// True for the names of the files a run writes (effective_case.yaml, points_0003.vtu, ...).
bool is_output_file_name(std::string_view name);

class OutputFolder {
 public:
  static constexpr const char* manifest_name = "unsatmpm_manifest.txt";
  static constexpr const char* lock_name = "unsatmpm.lock";

  /// A new run's folder, or the folder of a run to resume.
  enum class Claim { new_run, resume };

  /// Checks `dir`, creates it if absent, takes its lock and deletes the files of the earlier run
  /// listed in its manifest (Claim::resume: `dir` must hold a run's manifest and checkpoint, whose
  /// files are kept). Throws std::runtime_error, before touching anything, when the folder cannot
  /// be claimed.
  explicit OutputFolder(std::filesystem::path dir, Claim claim = Claim::new_run);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// The path of the output file `name`, listed in the manifest before it is first written.
  std::filesystem::path file(const std::string& name);
  /// True when the folder held the lock of an earlier run that did not end (killed, crashed).
  bool found_stale_lock() const { return stale_lock_; }

 private:
  void lock();
  void unlock();
  void append_to_manifest(const std::string& name) const;

  std::filesystem::path dir_;
  int lock_fd_ = -1;
  bool stale_lock_ = false;
  std::set<std::string> listed_;
};

}  // namespace unsatmpm
