#include "apps/plot.hpp"

#include <cstdlib>
#include <iostream>

#include "core/materials.hpp"

namespace imcol {

bool run_plot_script(const std::string& script, const std::filesystem::path& dir, const std::string& png) {
  const auto path = std::filesystem::path(data_dir()).parent_path() / "scripts" / script;
  const std::string cmd = "/usr/bin/python3 '" + path.string() + "' '" + dir.string() + "'";
  if (std::system(cmd.c_str()) == 0) {
    std::cout << "wrote " << (dir / png).string() << "\n";
    return true;
  }
  std::cerr << "imcol: warning: the plot failed (" << cmd << "); the data files are complete\n";
  return false;
}

}  // namespace imcol
