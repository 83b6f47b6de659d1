// The svgf binary as a process: what only a real process shows (exit status, a file size limit,
// signals). Each case fails on the code before issue 15's output rules.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "app/denoise_command.h"
#include "app_test_support.h"
#include "io/sequence.h"

namespace fs = std::filesystem;
using namespace svgf;
using test::file_bytes;
using test::read_json;
using test::scratch;

namespace {

// Starts `svgf args...` with stdout and stderr into `log`. max_file_bytes > 0 caps every file it
// writes (RLIMIT_FSIZE; SIGXFSZ ignored, so a write past the cap fails with EFBIG).
pid_t start_svgf(const std::vector<std::string>& args, const fs::path& log,
                 rlim_t max_file_bytes = 0) {
  std::vector<std::string> words = {SVGF_BINARY};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const std::string log_path = log.string();
  const pid_t pid = ::fork();
  if (pid == 0) {  // only async-signal-safe calls until exec
    const int fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) ::_exit(126);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    if (max_file_bytes > 0) {
      ::signal(SIGXFSZ, SIG_IGN);
      const rlimit cap{max_file_bytes, max_file_bytes};
      ::setrlimit(RLIMIT_FSIZE, &cap);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  REQUIRE(pid > 0);
  return pid;
}

// The exit status, or 1000 + the signal that killed it.
int wait_for(pid_t pid) {
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
}

}  // namespace

// Issue 15, item 3: report.json was written through an unchecked std::ofstream, so a full disk
// gave an empty or cut report, renamed into place, and exit status 0. Here a file size limit
// between the frames' size and the report's makes only the report's write fail (report.html,
// written before report.json through the same checked write, is the first to exceed it).
TEST_CASE("svgf denoise stops on a report it could not write", "[app][process]") {
  test::SyntheticScene small;
  small.width = 16;
  small.height = 12;
  small.square = 4;
  small.speed = 1;
  const fs::path in = test::write_synthetic(scratch("fsize_in"), 12, small);
  const fs::path out = scratch("fsize_out"), log = scratch("fsize_log");
  const std::vector<std::string> args = {"denoise", in.string(), out.string(), "--backend",
                                         "cpu", "--threads", "2", "--no-preview"};
  REQUIRE(app::denoise_command({args.begin() + 1, args.end()}) == 0);  // the previous output
  const auto before = test::snapshot(out);
  size_t largest_frame = 0;
  for (const auto& [name, bytes] : before)
    if (name.rfind("frame_", 0) == 0) largest_frame = std::max(largest_frame, bytes.size());
  REQUIRE(before.at("report.json").size() > largest_frame + 1024);  // room for a cap between
  REQUIRE(before.at("report.html").size() > largest_frame + 1024);  // written before report.json

  const pid_t pid = start_svgf(args, log, largest_frame + 512);
  REQUIRE(wait_for(pid) == 1);
  INFO(file_bytes(log));
  REQUIRE_THAT(file_bytes(log), Catch::Contains("report.html") && Catch::Contains("write error"));
  REQUIRE(test::snapshot(out) == before);
  REQUIRE(test::leftovers(out).empty());
  const auto failure = read_json(out.string() + ".failed-report.json");
  REQUIRE(failure["stage"] == "writing the report");
  REQUIRE_THAT(failure["error"].get<std::string>(), Catch::Contains("report.html"));
  fs::remove_all(in);
  fs::remove(log);
  test::remove_output(out);
}

// Issue 15, item 3: Ctrl-C killed the run with its outputs half-written into OUT_DIR. SIGINT now
// stops the run at the next frame: the staging folder is removed, the previous output stays
// byte for byte, a failure report says so, and the exit status is 128 + SIGINT = 130.
TEST_CASE("svgf denoise interrupted by SIGINT leaves no trace and exits with 130",
          "[app][process]") {
  test::SyntheticScene scene;
  scene.width = 128;
  scene.height = 96;
  scene.speed = 1;
  const int frames = 40;  // long enough that the signal lands well before the end
  const fs::path in = test::write_synthetic(scratch("sigint_in"), frames, scene);
  const fs::path out = scratch("sigint_out"), log = scratch("sigint_log");
  REQUIRE(app::denoise_command({in.string(), out.string(), "--backend", "cpu", "--threads", "2",
                                "--frames", "2"}) == 0);  // the previous output
  const auto before = test::snapshot(out);

  const pid_t pid = start_svgf({"denoise", in.string(), out.string(), "--backend", "cpu",
                                "--threads", "2"}, log);
  // Signalled once it is denoising: its second frame is in the staging folder.
  const fs::path second = out.string() + ".tmp-" + std::to_string(pid) + "/frame_0001.exr";
  int status = -1;
  for (int waited_ms = 0; waited_ms < 20000 && !fs::exists(second); ++waited_ms) {
    int raw = 0;
    if (::waitpid(pid, &raw, WNOHANG) == pid) {  // ended without ever writing a frame
      status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 1000 + WTERMSIG(raw);
      break;
    }
    ::usleep(1000);
  }
  if (status == -1) {
    ::kill(pid, SIGINT);
    status = wait_for(pid);
  }
  INFO(file_bytes(log));
  REQUIRE(status == 130);
  REQUIRE_THAT(file_bytes(log), Catch::Contains("interrupted by SIGINT"));
  REQUIRE(test::snapshot(out) == before);
  REQUIRE(test::leftovers(out).empty());
  const auto failure = read_json(out.string() + ".failed-report.json");
  REQUIRE(failure["exit_status"] == 130);
  REQUIRE(failure["stage"] == "denoising");
  REQUIRE(!failure.contains("frame"));  // stopped between frames
  REQUIRE(failure["frames_written"].get<int>() >= 2);
  REQUIRE(failure["frames_written"].get<int>() < frames);
  fs::remove_all(in);
  fs::remove(log);
  test::remove_output(out);
}
