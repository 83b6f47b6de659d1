#pragma once
// A folder written in full beside its destination and swapped in only when complete: the
// destination holds the old contents or the new, never a mix or a half (docs/frame-format.md,
// "Output folders").
#include <string>

namespace svgf::io {

// `dir` without a trailing separator or "." parts: the staging folder must be its sibling.
// Throws std::invalid_argument for "", "." and "..".
std::string normalized_folder(const std::string& dir);

// Why `dir` may not be replaced, or "" when it may: it is absent, an empty folder, or a folder
// holding `marker`, the file every folder of its kind has (manifest.json for a sequence,
// report.json for svgf denoise's output). A wrong path such as a home folder is never wiped.
std::string why_not_replaceable(const std::string& dir, const std::string& marker);

// True when `entry` (a file name) is a leftover of a writer into a folder named `name`:
// `name.tmp-PID` or `name.old-PID`.
bool is_staging_leftover(const std::string& entry, const std::string& name);

// Leftovers beside `dir` of writers that died without cleaning up (SIGKILL, power loss):
// `dir.tmp-PID` staging folders of processes no longer running are removed; an old folder
// `dir.old-PID` that such a process had moved aside comes back as `dir` when `dir` is missing
// (the process died between its two renames), and is removed otherwise. This process's own PID
// counts as dead: a folder with it was left by an earlier process.
void clean_stale_staging(const std::string& dir);

class StagedFolder {
 public:
  // Refuses (IoError) a `dir` that why_not_replaceable refuses, cleans stale leftovers and
  // creates the staging folder `dir.tmp-PID`.
  StagedFolder(const std::string& dir, const std::string& marker);
  ~StagedFolder();  // without commit(): removes the staging folder; `dir` is untouched
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  const std::string& dir() const { return dir_; }
  const std::string& path() const { return staging_; }  // write here
  // Moves an existing `dir` aside to `dir.old-PID`, renames the staging folder to `dir`, then
  // deletes the old folder. If the second rename fails, the old folder is moved back.
  void commit();

 private:
  std::string dir_, staging_, marker_;
  bool committed_ = false;
};

}  // namespace svgf::io
