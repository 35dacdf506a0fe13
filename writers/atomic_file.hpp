// Atomic file writes: every output file is written to NAME.tmp in the same folder and then
// renamed onto NAME, so a crash or a full disk never leaves a truncated file. Failures throw
// std::runtime_error naming the file and the operating system's reason.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace unsatmpm {

/// 'PATH', for messages.
std::string quoted_path(const std::filesystem::path& p);

/// Calls `write(tmp)` with tmp = file + ".tmp", then renames tmp onto `file`. If `write` throws or
/// the rename fails, the temporary is removed and `file` is left untouched.
void write_file_atomically(const std::filesystem::path& file,
                           const std::function<void(const std::filesystem::path& tmp)>& write);

/// Writes `text` to `file` atomically (see write_file_atomically).
void write_text_atomically(const std::filesystem::path& file, std::string_view text);

}  // namespace unsatmpm
