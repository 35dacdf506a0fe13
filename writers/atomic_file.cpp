#include "writers/atomic_file.hpp"

#include <cerrno>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace unsatmpm {

namespace fs = std::filesystem;

std::string quoted_path(const fs::path& p) {
  std::string out(1, '\'');  // append, not "'" + string&&: GCC 12's false -Wrestrict (bug 105329)
  return out.append(p.string()).append(1, '\'');
}

void write_file_atomically(const fs::path& file,
                           const std::function<void(const fs::path& tmp)>& write) {
  const fs::path folder = file.parent_path();
  std::error_code ec;
  if (!folder.empty() && !fs::is_directory(folder, ec))
    throw std::runtime_error("cannot write " + quoted_path(file) + ": folder " +
                             quoted_path(folder) + " is not an existing folder");
  fs::path tmp = file;
  tmp += ".tmp";
  // Only a regular file can be ours to delete; anything else at tmp makes the write fail anyway.
  const auto remove_tmp = [&tmp] {
    std::error_code ignored;
    if (fs::is_regular_file(tmp, ignored)) fs::remove(tmp, ignored);
  };
  try {
    write(tmp);
  } catch (...) {
    remove_tmp();
    throw;
  }
  fs::rename(tmp, file, ec);
  if (ec) {
    remove_tmp();
    throw std::runtime_error("cannot write " + quoted_path(file) + ": renaming " +
                             quoted_path(tmp) + " failed: " + ec.message());
  }
}

void write_text_atomically(const fs::path& file, std::string_view text) {
  write_file_atomically(file, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (out) out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (out) out.close();
    if (!out)
      throw std::runtime_error("cannot write " + quoted_path(file) + " (via " + quoted_path(tmp) +
                               "): " + std::generic_category().message(errno));
  });
}

}  // namespace unsatmpm
