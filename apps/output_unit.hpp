// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A command's output folder as one unit: all of one run's files or none of them.
//
// The files are built in a staging folder beside the target (`.NAME.part-PID`) and swapped in by one rename
// (renameat2 RENAME_EXCHANGE), so a reader, a crash or kill -9 never sees files of two runs side by side. An
// exclusive lock (flock) on the target folder refuses a second writer; the lock holder removes the staging
// folders that killed runs left behind. `.imcol-run.json` in the folder names the run that wrote it and lists its
// files: a folder is replaced only when it is empty or holds exactly what its marker lists, never when it holds an
// input of the run. A name of the staging form (`.NAME.part-N`, `.NAME.old-N`) is refused as an output folder.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace imcol {

/// The command line of this process, recorded in every output folder (set once by run_cli).
void set_command_line(int argc, char** argv);

/// A file the run reads, which its output folder must not hold: `what` names it in messages ("--cache").
struct RunInput {
  std::string what, path;
};

class OutputUnit {
 public:
  /// `out`: the --out value, or empty for `fallback`. Errors (exit 2) name `--out`, or the scene key 'name' of
  /// `scene_path` when the folder comes from the scene's name. Refuses a folder another imcol process is writing,
  /// the current folder or one that contains it, a folder holding files imcol did not write, and one that holds
  /// the scene file or one of `inputs`.
  OutputUnit(const std::string& out, const std::filesystem::path& fallback, const std::string& scene_path = "",
             const std::vector<RunInput>& inputs = {});
  ~OutputUnit();
  OutputUnit(const OutputUnit&) = delete;
  OutputUnit& operator=(const OutputUnit&) = delete;

  /// Where to write now (the staging folder).
  const std::filesystem::path& dir() const { return staging_; }
  /// Where the files will be once committed, as given (relative paths stay relative).
  const std::filesystem::path& target() const { return shown_; }
  /// The run that writes this unit: id, command, imcol version, host, pid, start time (UTC).
  const nlohmann::ordered_json& run() const { return run_; }

  /// Swaps the staged files in as the folder's whole content (the previous content is removed). Throws
  /// std::runtime_error if the swap fails (the target then keeps its previous content).
  void commit();

  /// Keeps the staged files of a run that could not finish beside the target, as `NAME.partial-ID` (ID: the
  /// run's id), and leaves the target's previous content as it was. Returns that folder's path as shown; throws
  /// std::runtime_error if it cannot be moved (the staged files are then removed).
  std::filesystem::path keep_beside();

 private:
  void refuse_staging_name() const;
  void refuse_inputs_inside(const std::string& scene_path, const std::vector<RunInput>& inputs) const;
  void lock_target();
  void check_contents() const;
  void remove_leftovers() const;
  void write_marker(bool complete) const;
  std::filesystem::path move_beside(const std::string& kind);
  std::filesystem::path sibling(const std::string& kind, long pid) const;

  std::filesystem::path shown_, target_, staging_;  // as given; absolute; where the files are built
  std::vector<std::filesystem::path> created_;  // folders this created for the target, innermost first
  std::string place_, key_;                     // where the folder came from, for messages
  nlohmann::ordered_json run_;
  int lock_fd_ = -1;
  bool committed_ = false;
};

}  // namespace imcol
