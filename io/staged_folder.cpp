#include "io/staged_folder.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "io/io_error.h"

namespace svgf::io {
namespace fs = std::filesystem;
namespace {

std::string pid_suffix() { return std::to_string(static_cast<long>(::getpid())); }

// The PID in "NAME.tmp-PID" (tag ".tmp-"), or 0 when `entry` is not such a name.
long pid_in(const std::string& entry, const std::string& name, const std::string& tag) {
  const std::string prefix = name + tag;
  if (entry.size() <= prefix.size() || entry.compare(0, prefix.size(), prefix) != 0) return 0;
  const std::string digits = entry.substr(prefix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) return 0;
  return std::strtol(digits.c_str(), nullptr, 10);
}

bool process_running(long pid) {
  if (pid == static_cast<long>(::getpid())) return false;  // an earlier process with our PID
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

}  // namespace

std::string normalized_folder(const std::string& dir) {
  fs::path p = fs::path(dir).lexically_normal();
  if (!p.has_filename()) p = p.parent_path();  // "a/b/" -> "a/b"
  if (p.empty() || p == "." || p == "..")
    throw std::invalid_argument("invalid folder '" + dir + "'");
  return p.string();
}

bool is_staging_leftover(const std::string& entry, const std::string& name) {
  return pid_in(entry, name, ".tmp-") > 0 || pid_in(entry, name, ".old-") > 0;
}

std::string why_not_replaceable(const std::string& dir, const std::string& marker) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return "";
  if (!fs::is_directory(dir, ec)) return dir + ": exists and is not a folder; refusing to replace it";
  if (!fs::is_empty(dir, ec) && !fs::exists(fs::path(dir) / marker, ec))
    return dir + ": exists and holds no " + marker + "; refusing to replace it";
  return "";
}

void clean_stale_staging(const std::string& dir) {
  const fs::path target(dir);
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string name = target.filename().string();
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const std::string entry_name = entry.path().filename().string();
    std::error_code ignored;
    if (const long pid = pid_in(entry_name, name, ".tmp-"); pid > 0 && !process_running(pid)) {
      fs::remove_all(entry.path(), ignored);
    } else if (const long old = pid_in(entry_name, name, ".old-"); old > 0 && !process_running(old)) {
      if (!fs::exists(target, ignored))
        fs::rename(entry.path(), target, ignored);  // the previous output comes back
      else
        fs::remove_all(entry.path(), ignored);
    }
  }
}

StagedFolder::StagedFolder(const std::string& dir, const std::string& marker)
    : dir_(normalized_folder(dir)), staging_(dir_ + ".tmp-" + pid_suffix()), marker_(marker) {
  clean_stale_staging(dir_);  // first: it may bring back a `dir` that a dead process moved aside
  if (const std::string why = why_not_replaceable(dir_, marker_); !why.empty()) throw IoError(why);
  try {
    fs::remove_all(staging_);
    fs::create_directories(staging_);
  } catch (const fs::filesystem_error& e) {
    throw IoError(staging_ + ": cannot create folder: " + e.code().message());
  }
}

StagedFolder::~StagedFolder() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

void StagedFolder::commit() {
  if (committed_) throw std::logic_error(dir_ + ": StagedFolder::commit called twice");
  // Checked again: the folder may have changed since the constructor.
  if (const std::string why = why_not_replaceable(dir_, marker_); !why.empty()) throw IoError(why);
  // Moved aside rather than deleted first: if the rename fails it comes back.
  const std::string old_dir = dir_ + ".old-" + pid_suffix();
  std::error_code ec;
  const bool had_old = fs::exists(dir_, ec);
  if (had_old) {
    fs::remove_all(old_dir, ec);
    fs::rename(dir_, old_dir, ec);
    if (ec) throw IoError(dir_ + ": cannot move the existing folder aside: " + ec.message());
  }
  fs::rename(staging_, dir_, ec);
  if (ec) {
    std::error_code ignored;
    if (had_old) fs::rename(old_dir, dir_, ignored);
    throw IoError(dir_ + ": cannot rename " + staging_ + " into place: " + ec.message());
  }
  committed_ = true;
  if (had_old) fs::remove_all(old_dir, ec);
}

}  // namespace svgf::io
