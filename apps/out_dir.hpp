#pragma once
// The output directory of a command, created before anything runs.
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "core/errors.hpp"

namespace imcol {

/// The output directory, created before anything runs (a bad --out or name fails at once, exit 2). If the run
/// fails before anything is written, the directories this created are removed again (no empty folder is left).
class OutDir {
 public:
  OutDir(const std::string& out, const std::filesystem::path& fallback) : dir_(out.empty() ? fallback : std::filesystem::path(out)) {
    namespace fs = std::filesystem;
    for (fs::path p = dir_; !p.empty() && !fs::exists(p); p = p.parent_path()) {
      created_.push_back(p);
      if (p == p.parent_path()) break;
    }
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec || !fs::is_directory(dir_))
      throw InputError(out.empty() ? "scene key 'name'" : "command line", out.empty() ? "name" : "--out",
                       "cannot create the output directory '" + dir_.string() + "'" + (ec ? ": " + ec.message() : ""));
  }
  ~OutDir() {
    if (kept_) return;
    std::error_code ec;
    for (const auto& p : created_)  // innermost first; fs::remove deletes only empty directories
      if (!std::filesystem::is_directory(p, ec) || !std::filesystem::is_empty(p, ec) || !std::filesystem::remove(p, ec)) break;
  }
  OutDir(const OutDir&) = delete;
  OutDir& operator=(const OutDir&) = delete;
  const std::filesystem::path& path() const { return dir_; }
  void keep() { kept_ = true; }

 private:
  std::filesystem::path dir_;
  std::vector<std::filesystem::path> created_;
  bool kept_ = false;
};

}  // namespace imcol
