// SPDX-License-Identifier: BSD-3-Clause
#include "core/text_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "core/errors.hpp"

namespace imcol {

std::string byte_count_text(std::uintmax_t bytes) {
  constexpr std::uintmax_t KiB = 1024, MiB = KiB * KiB, GiB = MiB * KiB;
  if (bytes >= GiB && bytes % GiB == 0) return std::to_string(bytes / GiB) + " GiB";
  if (bytes >= MiB && bytes % MiB == 0) return std::to_string(bytes / MiB) + " MiB";
  if (bytes >= KiB && bytes % KiB == 0) return std::to_string(bytes / KiB) + " KiB";
  return std::to_string(bytes) + " bytes";
}

std::string read_text_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes, const std::string& format,
                           const std::string& key) {
  const std::string file = what + " file";
  auto fail = [&](const std::string& problem) -> void { throw InputError(path, key, problem); };
  auto not_regular = [&](const struct stat& st) {
    if (S_ISDIR(st.st_mode)) fail("is a directory, not a " + file);
    if (!S_ISREG(st.st_mode))
      fail("is not a regular file (a " + what + " is a " + (format.empty() ? "" : format + " ") + "text file)");
  };
  auto too_large = [&](std::uintmax_t size) {
    fail("the " + file + " has " + std::to_string(size) + " bytes, more than the " + byte_count_text(max_bytes) + " a " + what +
         " may have");
  };
  // Checked before opening: opening a FIFO for reading would wait for a writer.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) fail("cannot open the " + file + " (no such file)");
    fail("cannot read the " + file + ": " + std::strerror(errno));
  }
  not_regular(st);
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) too_large(static_cast<std::uintmax_t>(st.st_size));
  // O_NONBLOCK: a FIFO put in the file's place since then does not block the open; fstat refuses it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) fail("cannot open the " + file + ": " + std::strerror(errno));
  std::string text;
  try {
    if (::fstat(fd, &st) != 0) fail("cannot read the " + file + ": " + std::strerror(errno));
    not_regular(st);
    // Read at most one byte past the bound: a file grown since the stat is refused all the same.
    text.resize(static_cast<std::size_t>(st.st_size) + 1);
    std::size_t got = 0;
    for (;;) {
      if (got == text.size()) {
        if (got > max_bytes) too_large(got);
        text.resize(std::min<std::uintmax_t>(2 * text.size(), max_bytes + 1));
      }
      const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) fail("cannot read the " + file + ": " + std::strerror(errno));
      if (n == 0) break;
      got += static_cast<std::size_t>(n);
    }
    text.resize(got);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return text;
}

}  // namespace imcol
