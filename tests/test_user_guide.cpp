// SPDX-License-Identifier: BSD-3-Clause
// The user's guide runs as written: the README's example scene and the scene reference's full template
// are extracted from the Markdown and run with `imcol run` (exit status 0, e measured).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "core/materials.hpp"
#include "tests/imcol_process.hpp"

namespace fs = std::filesystem;
using imcol::test::slurp;

namespace {

/// The first ```toml block after `marker` in the Markdown file `doc` (relative to the source tree).
std::string toml_block(const std::string& doc, const std::string& marker) {
  const std::string text = slurp(fs::path(imcol::data_dir()).parent_path() / doc);
  const auto at = text.find(marker);
  if (at == std::string::npos) {
    ADD_FAILURE() << doc << ": marker '" << marker << "' not found";
    return "";
  }
  std::smatch m;
  const std::string rest = text.substr(at);
  if (!std::regex_search(rest, m, std::regex("```toml\\n([\\s\\S]*?)```"))) {
    ADD_FAILURE() << doc << ": no toml block after '" << marker << "'";
    return "";
  }
  return m[1].str();
}

/// Runs the scene text; returns the summary (and checks exit status 0).
nlohmann::json run_scene(const std::string& text, const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("imcol_guide_" + tag + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path scene = dir / "scene.toml";
  std::ofstream(scene) << text;
  const std::string cmd = std::string(IMCOL_BINARY) + " run " + scene.string() + " --no-plot --quiet --out " + (dir / "out").string() +
                          " 2>" + (dir / "err").string();
  const int raw = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << tag << ": " << slurp(dir / "err");
  nlohmann::json s;
  if (fs::exists(dir / "out" / "summary.json")) s = nlohmann::json::parse(slurp(dir / "out" / "summary.json"));
  fs::remove_all(dir);
  return s;
}

}  // namespace

TEST(UserGuide, ReadmeExampleSceneRuns) {
  const std::string text = toml_block("README.md", "<!-- example-scene");
  ASSERT_FALSE(text.empty());
  const auto s = run_scene(text, "readme");
  ASSERT_TRUE(s.contains("e") && s["e"].is_number()) << s.dump();
  EXPECT_GT(s["e"].get<double>(), 0.0);
  EXPECT_LT(s["e"].get<double>(), 0.97);
  EXPECT_NE(s["effects"].dump().find("history"), std::string::npos);  // the default model includes it
}

TEST(UserGuide, SceneReferenceTemplateRuns) {
  const std::string text = toml_block("docs/scene-reference.md", "## Every key");
  ASSERT_FALSE(text.empty());
  const auto s = run_scene(text, "reference");
  ASSERT_TRUE(s.contains("e") && s["e"].is_number()) << s.dump();
  EXPECT_GT(s["e"].get<double>(), 0.0);
}

TEST(UserGuide, ReadmeStatesTheProgramsVersion) {
  // README's first paragraph: "Version X.Y.Z (`imcol --version`; …)": the version the program prints.
  const std::string readme = slurp(fs::path(imcol::data_dir()).parent_path() / "README.md");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(readme, m, std::regex("\\nVersion ([0-9]+\\.[0-9]+\\.[0-9]+) ")));
  const auto v = imcol::test::run_imcol("--version", fs::temp_directory_path() / "imcol_readme_version");
  ASSERT_EQ(v.status, 0) << v.err;
  EXPECT_EQ(v.out, "imcol " + m[1].str() + "\n");
}

TEST(UserGuide, ReadmeLayoutNamesEveryModuleAndLinksTheArchitecture) {
  const fs::path root = fs::path(imcol::data_dir()).parent_path();
  const std::string readme = slurp(root / "README.md");
  const auto layout = readme.find("## Layout");
  ASSERT_NE(layout, std::string::npos);
  const std::string section = readme.substr(layout, readme.find("\n## ", layout + 1) - layout);
  EXPECT_NE(section.find("docs/architecture.md"), std::string::npos);
  // Every folder with a CMakeLists.txt of its own (a module) is named there.
  for (const auto& d : fs::directory_iterator(root)) {
    const std::string name = d.path().filename().string();
    if (!d.is_directory() || !fs::exists(d.path() / "CMakeLists.txt") || name.rfind("build", 0) == 0) continue;
    EXPECT_NE(section.find(name + "/"), std::string::npos) << name;
  }
}
