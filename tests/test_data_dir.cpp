// SPDX-License-Identifier: BSD-3-Clause
// The data folder's precedence (core/data_dir.hpp): $IMCOL_DATA_DIR, then set_data_dir's folder, then the source
// tree's data/; the shipped scenes are found through it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "core/data_dir.hpp"
#include "core/scene_files.hpp"

namespace fs = std::filesystem;

namespace {

/// Unsets IMCOL_DATA_DIR and clears the setter for one test; restores both after it.
class DataDirScope {
 public:
  DataDirScope() {
    if (const char* d = std::getenv("IMCOL_DATA_DIR")) env_ = d;
    ::unsetenv("IMCOL_DATA_DIR");
    imcol::set_data_dir("");
  }
  ~DataDirScope() {
    imcol::set_data_dir("");
    if (env_) ::setenv("IMCOL_DATA_DIR", env_->c_str(), 1);
    else ::unsetenv("IMCOL_DATA_DIR");
  }
  DataDirScope(const DataDirScope&) = delete;
  DataDirScope& operator=(const DataDirScope&) = delete;

 private:
  std::optional<std::string> env_;
};

}  // namespace

TEST(DataDir, CompileTimeFolderWhenNothingIsSet) {
  DataDirScope scope;
  EXPECT_EQ(imcol::data_dir(), std::string(IMCOL_DATA_DIR));
  EXPECT_TRUE(fs::exists(fs::path(imcol::data_dir()) / "scenes" / "default.toml"));
}

TEST(DataDir, SetterOverridesTheCompileTimeFolderAndEmptyClearsIt) {
  DataDirScope scope;
  imcol::set_data_dir("/opt/imcol-data");
  EXPECT_EQ(imcol::data_dir(), "/opt/imcol-data");
  EXPECT_EQ(imcol::scenes_dir(), "/opt/imcol-data/scenes");
  imcol::set_data_dir("");
  EXPECT_EQ(imcol::data_dir(), std::string(IMCOL_DATA_DIR));
}

TEST(DataDir, EnvironmentOverridesTheSetterUnlessEmpty) {
  DataDirScope scope;
  imcol::set_data_dir("/opt/imcol-data");
  ::setenv("IMCOL_DATA_DIR", "/srv/data", 1);
  EXPECT_EQ(imcol::data_dir(), "/srv/data");
  ::setenv("IMCOL_DATA_DIR", "", 1);
  EXPECT_EQ(imcol::data_dir(), "/opt/imcol-data");
}
