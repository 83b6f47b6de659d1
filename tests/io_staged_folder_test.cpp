// Output folders that are whole or absent: io::StagedFolder, its stale-leftover cleaning, and
// checked atomic file writes (issue 15, "never leave a lie").
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "io/atomic_file.h"
#include "io/io_error.h"
#include "io/staged_folder.h"

#include "file_test_support.h"

namespace fs = std::filesystem;
using namespace svgf;
using Catch::Matchers::Contains;

namespace {

fs::path fresh(const std::string& name) {
  const fs::path p = fs::temp_directory_path() /
                     ("svgf_staged_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

using svgf::test::list_dir;
using svgf::test::read_text;
using svgf::test::write_text;

// A PID no process can have: above the kernel's limit.
long dead_pid() {
  long max = 4194304;
  std::ifstream("/proc/sys/kernel/pid_max") >> max;
  return max + 1;
}

}  // namespace

TEST_CASE("StagedFolder: the old folder until commit, then the new one whole", "[io][staged]") {
  const fs::path root = fresh("commit");
  const fs::path out = root / "out";
  fs::create_directories(out);
  write_text(out / "report.json", "old");
  {
    io::StagedFolder staged(out.string() + "/", "report.json");  // trailing slash: same folder
    REQUIRE(staged.dir() == out.string());
    write_text(fs::path(staged.path()) / "report.json", "new");
    REQUIRE(read_text(out / "report.json") == "old");
    REQUIRE(list_dir(root) == std::set<std::string>{"out", "out.tmp-" + std::to_string(::getpid())});
    staged.commit();
  }
  REQUIRE(list_dir(root) == std::set<std::string>{"out"});
  REQUIRE(read_text(out / "report.json") == "new");
  {
    io::StagedFolder abandoned(out.string(), "report.json");
    write_text(fs::path(abandoned.path()) / "report.json", "never");
  }
  REQUIRE(list_dir(root) == std::set<std::string>{"out"});
  REQUIRE(read_text(out / "report.json") == "new");
  // A folder without the marker is not this kind of output: refused, left alone.
  fs::create_directories(root / "precious");
  write_text(root / "precious" / "keep.txt", "keep");
  REQUIRE_THROWS_WITH(io::StagedFolder((root / "precious").string(), "report.json"),
                      Contains("precious") && Contains("holds no report.json"));
  REQUIRE(read_text(root / "precious" / "keep.txt") == "keep");
  fs::remove_all(root);
}

// SIGKILL or a power cut leaves the staging folder (and, between the two renames, the old folder
// moved aside). The next writer removes a dead process's leftovers and puts back an old folder
// whose replacement never arrived; a live process's staging folder is left alone.
TEST_CASE("clean_stale_staging removes dead writers' leftovers only", "[io][staged]") {
  const fs::path root = fresh("stale");
  const std::string dead = std::to_string(dead_pid()), alive = std::to_string(::getppid());
  for (const std::string& name : {"out.tmp-" + dead, "out.tmp-" + alive, "out.old-" + dead,
                                 std::string("out.tmp-x1"), "outer.tmp-" + dead, std::string("keep")}) {
    fs::create_directories(root / name);
    write_text(root / name / "report.json", name);
  }
  SECTION("the output missing: the old folder comes back") {
    io::clean_stale_staging((root / "out").string());
    REQUIRE(list_dir(root) == std::set<std::string>{"out", "out.tmp-" + alive, "out.tmp-x1",
                                                    "outer.tmp-" + dead, "keep"});
    REQUIRE(read_text(root / "out" / "report.json") == "out.old-" + dead);
  }
  SECTION("the output present: the old folder goes") {
    fs::create_directories(root / "out");
    io::clean_stale_staging((root / "out").string());
    REQUIRE(list_dir(root) == std::set<std::string>{"out", "out.tmp-" + alive, "out.tmp-x1",
                                                    "outer.tmp-" + dead, "keep"});
    REQUIRE(fs::is_empty(root / "out"));
  }
  fs::remove_all(root);
}

// An unchecked stream turned a failed write into an empty report renamed into place. A file size
// limit (RLIMIT_FSIZE, applied to root too) makes the write fail for real.
TEST_CASE("write_file_atomically reports a failed write and leaves no file", "[io][atomic]") {
  const fs::path root = fresh("short_write");
  const fs::path path = root / "report.json";
  write_text(path, "previous");
  rlimit saved{};
  REQUIRE(::getrlimit(RLIMIT_FSIZE, &saved) == 0);
  void (*saved_handler)(int) = ::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of a signal
  rlimit small = saved;
  small.rlim_cur = 100;
  REQUIRE(::setrlimit(RLIMIT_FSIZE, &small) == 0);
  std::string message;
  try {
    io::write_file_atomically(path.string(), std::string(4096, 'x'));
  } catch (const io::IoError& e) {
    message = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &saved);
  ::signal(SIGXFSZ, saved_handler);
  REQUIRE_THAT(message, Contains(path.string()) && Contains("write error"));
  REQUIRE(read_text(path) == "previous");
  REQUIRE(list_dir(root) == std::set<std::string>{"report.json"});
  io::write_file_atomically(path.string(), "next");
  REQUIRE(read_text(path) == "next");
  fs::remove_all(root);
}
