// svgf denoise's frame pipeline (issue 14, item 4): reading, denoising and writing overlap, with
// the same bits, the same report and the same failures as one frame after another.
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

#include "app/denoise_command.h"
#include "app/frame_pipeline.h"
#include "app/frame_timing.h"
#include "app/method_options.h"
#include "app_test_support.h"
#include "cli/command_line.h"
#include "core/order_stats.h"
#include "io/exr_frame.h"
#include "io/sequence.h"
#include "pipeline/make_denoiser.h"

namespace fs = std::filesystem;
using namespace svgf;
using app::FrameStep;
using app::StageFailure;
using test::file_bytes;
using test::read_json;
using test::scratch;

namespace {

const fs::path kCut = fs::path(SVGF_SOURCE_DIR) / "fixtures" / "cut";  // a camera cut at frame 6

// What the three stages saw, in the order they saw it.
struct Trace {
  std::mutex mutex;
  std::vector<std::string> events;  // "r3", "p3", "f3", "F3 read" (finish of a failed item)
  void add(std::string e) {
    const std::lock_guard<std::mutex> lock(mutex);
    events.push_back(std::move(e));
  }
  std::vector<std::string> of(char stage) {
    std::vector<std::string> out;
    for (const std::string& e : events)
      if (e[0] == stage) out.push_back(e);
    return out;
  }
};

struct Item {
  int index = -1;
  std::shared_ptr<int> held;  // counts the items alive: none may outlive the run
};

// Runs `count` items through the pipeline, tracing them; `fail_read`, `fail_process` and
// `fail_finish`: the item whose stage throws (-1: none).
void traced_run(Trace& trace, const std::shared_ptr<int>& held, int count, int in_flight,
                int fail_read = -1, int fail_process = -1, int fail_finish = -1) {
  app::run_frame_pipeline<Item>(
      count, in_flight,
      [&](int k, Item& item) {
        trace.add("r" + std::to_string(k));
        item.index = k;
        item.held = held;
        if (k == fail_read) throw std::runtime_error("read " + std::to_string(k));
      },
      [&](Item& item) {
        trace.add("p" + std::to_string(item.index));
        if (item.index == fail_process) throw std::runtime_error("process " + std::to_string(item.index));
      },
      [&](Item& item, const StageFailure& failure) {
        if (failure.error) {
          trace.add("F" + std::to_string(item.index) + " " + app::to_string(failure.step));
          return;
        }
        trace.add("f" + std::to_string(item.index));
        if (item.index == fail_finish) throw std::runtime_error("finish " + std::to_string(item.index));
      });
}

std::vector<std::string> numbered(char stage, int from, int to) {
  std::vector<std::string> out;
  for (int k = from; k < to; ++k) out.push_back(stage + std::to_string(k));
  return out;
}

// The fixture's 12 frames and manifest in a scratch folder, to be spoiled.
fs::path copy_of_cut(const std::string& name) {
  const fs::path dir = scratch(name);
  fs::create_directories(dir);
  for (const auto& e : fs::directory_iterator(kCut)) fs::copy_file(e.path(), dir / e.path().filename());
  return dir;
}

// report.json without what is timed: what a run with any number of frames in flight must match.
nlohmann::json untimed(nlohmann::json report) {
  report.erase("timing");
  report.erase("mean_time_ms");
  for (auto& f : report["frames"])
    for (const char* key : {"time_ms", "filter_ms", "stage_ms", "read_ms", "write_ms"}) f.erase(key);
  return report;
}

// report.csv without its two time columns (time_ms, filter_ms).
std::string untimed_csv(const std::string& csv) {
  std::string out, line;
  for (size_t start = 0; start < csv.size();) {
    const size_t end = csv.find('\n', start);
    line = csv.substr(start, end - start);
    const size_t a = line.find(','), b = line.find(',', a + 1), c = line.find(',', b + 1);
    out += line.substr(0, a) + line.substr(c) + "\n";
    start = end == std::string::npos ? csv.size() : end + 1;
  }
  return out;
}

// Runs the svgf binary with stderr joined to stdout; returns what it printed.
std::string run_binary(const std::string& args, int& status) {
  std::string out;
  std::FILE* p = ::popen((std::string(SVGF_BINARY) + " " + args + " 2>&1").c_str(), "r");
  REQUIRE(p != nullptr);
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  status = ::pclose(p);
  return out;
}

}  // namespace

TEST_CASE("run_frame_pipeline: each stage sees every item in order, at most in_flight at once",
          "[app][pipeline]") {
  for (int in_flight : {1, 2, 3}) {
    INFO("in flight " << in_flight);
    Trace trace;
    auto held = std::make_shared<int>(0);
    traced_run(trace, held, 20, in_flight);
    REQUIRE(trace.of('r') == numbered('r', 0, 20));
    REQUIRE(trace.of('p') == numbered('p', 0, 20));
    REQUIRE(trace.of('f') == numbered('f', 0, 20));
    // Item k + in_flight is read only after item k is finished.
    int live = 0, most = 0;
    for (const std::string& e : trace.events) {
      live += e[0] == 'r' ? 1 : e[0] == 'f' ? -1 : 0;
      most = std::max(most, live);
    }
    REQUIRE(most <= in_flight);
    REQUIRE(held.use_count() == 1);
    if (in_flight == 1) {  // the plain loop: read, process, finish, then the next item
      std::vector<std::string> loop;
      for (int k = 0; k < 20; ++k)
        for (char stage : {'r', 'p', 'f'}) loop.push_back(stage + std::to_string(k));
      REQUIRE(trace.events == loop);
    }
  }
}

TEST_CASE("run_frame_pipeline: the next item is read while one is being processed",
          "[app][pipeline]") {
  if (tbb::this_task_arena::max_concurrency() < 2) {
    WARN("SKIPPED: one thread, nothing can overlap");
    return;
  }
  std::mutex mutex;
  std::condition_variable changed;
  bool read_1 = false, overlapped = false;
  app::run_frame_pipeline<Item>(
      3, 3,
      [&](int k, Item& item) {
        item.index = k;
        const std::lock_guard<std::mutex> lock(mutex);
        if (k == 1) read_1 = true;
        changed.notify_all();
      },
      [&](Item& item) {
        if (item.index != 0) return;
        std::unique_lock<std::mutex> lock(mutex);  // item 0: wait for item 1's read
        overlapped = changed.wait_for(lock, std::chrono::seconds(30), [&] { return read_1; });
      },
      [](Item&, const StageFailure&) {});
  REQUIRE(overlapped);  // one frame after another, item 1 is read only after item 0 is written
}

TEST_CASE("run_frame_pipeline: a failure reaches the last stage with its item, after every "
          "earlier item, and nothing after it is finished", "[app][pipeline]") {
  auto held = std::make_shared<int>(0);
  {
    Trace trace;
    REQUIRE_THROWS_WITH(traced_run(trace, held, 8, 3, /*fail_read=*/3), "read 3");
    REQUIRE(trace.of('r') == numbered('r', 0, 4));  // none read after the failed one
    REQUIRE(trace.of('p') == numbered('p', 0, 3));  // the failed one is not processed
    REQUIRE(trace.of('f') == numbered('f', 0, 3));
    REQUIRE(trace.of('F') == std::vector<std::string>{"F3 read"});
    REQUIRE(trace.events.back() == "F3 read");
  }
  {
    Trace trace;
    REQUIRE_THROWS_WITH(traced_run(trace, held, 8, 3, -1, /*fail_process=*/2), "process 2");
    REQUIRE(trace.of('f') == numbered('f', 0, 2));
    REQUIRE(trace.of('F') == std::vector<std::string>{"F2 denoise"});
    // Nothing is processed or finished after the failure; a read begun before item 2 failed
    // (item 3's, on the first stage's thread) may still end after it.
    const auto failed = std::find(trace.events.begin(), trace.events.end(), "F2 denoise");
    for (auto e = failed + 1; e != trace.events.end(); ++e) REQUIRE((*e)[0] == 'r');
    REQUIRE(trace.of('p') == numbered('p', 0, 3));  // none processed after the failed one
    REQUIRE(trace.of('r').size() <= 5);  // at most items 3 and 4 were read besides
  }
  {
    Trace trace;
    REQUIRE_THROWS_WITH(traced_run(trace, held, 8, 3, -1, -1, /*fail_finish=*/1), "finish 1");
    REQUIRE(trace.of('f') == numbered('f', 0, 2));
  }
  REQUIRE(held.use_count() == 1);  // no item left behind by a cancelled pipeline
}

TEST_CASE("frame timing: medians, the stages' sum against the wall time", "[app][pipeline]") {
  CHECK(order_stats({}).median == 0);
  CHECK(order_stats({3, 1, 2}).median == 2);
  CHECK(order_stats({4, 1, 3, 2}).median == 2.5);
  const app::TimingSummary t = app::summarize_timing({{1, 2, 3}, {3, 4, 5}, {2, 9, 4}}, 12, 3);
  CHECK(t.median_read_ms == 2);
  CHECK(t.median_denoise_ms == 4);
  CHECK(t.median_write_ms == 4);
  CHECK(t.stage_sum_ms_per_frame == 11);
  CHECK(t.wall_ms_per_frame == 4);
  CHECK(t.speedup == 33.0 / 12.0);
  CHECK(app::to_json(t)["frames_in_flight"] == 3);
}

TEST_CASE("svgf denoise pipelined: the same bits and report as one frame at a time",
          "[app][pipeline]") {
  const fs::path piped = scratch("piped_out"), single = scratch("single_out");
  for (const auto& [out, in_flight] : {std::pair{piped, "3"}, std::pair{single, "1"}})
    REQUIRE(app::denoise_command({kCut.string(), out.string(), "--backend", "cpu", "--threads",
                                  "2", "--frames", "8", "--frames-in-flight", in_flight}) == 0);
  const auto a = test::snapshot(piped), b = test::snapshot(single);
  REQUIRE(a.size() == b.size());
  REQUIRE(a.size() == 8 + 8 + 3);  // frames, previews, report.json, .csv, .html
  for (const auto& [name, bytes] : a) {
    INFO(name);
    REQUIRE(b.count(name));
    if (name.rfind("report.", 0) != 0) REQUIRE(bytes == b.at(name));
  }
  REQUIRE(untimed(read_json(piped / "report.json")) == untimed(read_json(single / "report.json")));
  REQUIRE(untimed_csv(a.at("report.csv")) == untimed_csv(b.at("report.csv")));
  REQUIRE(read_json(piped / "report.json")["frames"][6]["history_reset"] == "camera cut");

  // And the library's own loop, one frame after another with the reset at the cut.
  CLI::App command_line;
  app::MethodParamFlags flags;
  flags.add_to(command_line);
  cli::parse(command_line, {});
  DenoiserConfig config;
  config.method = parse_method("svgf");
  config.backend = Backend::Cpu;
  config.threads = 2;
  flags.read(config);
  const std::unique_ptr<Denoiser> denoiser = make_denoiser(config);
  const io::Sequence sequence(kCut.string());
  Image out;
  for (int k = 0; k < 8; ++k) {
    INFO("frame " << k);
    if (k == 6) denoiser->reset();
    denoiser->denoise(sequence.read(k), out);
    const Image written = io::read_rgb_exr((piped / io::frame_file_name(k)).string());
    REQUIRE(written.data().size() == out.data().size());
    REQUIRE(std::memcmp(written.data().data(), out.data().data(), out.data().size() * sizeof(float)) == 0);
  }
  test::remove_output(piped);
  test::remove_output(single);
}

TEST_CASE("svgf denoise pipelined: a bad frame in the middle is the one the failure report "
          "names, and OUT_DIR is left as it was", "[app][pipeline]") {
  const fs::path in = copy_of_cut("pipe_bad_in"), out = scratch("pipe_bad_out");
  REQUIRE(app::denoise_command({in.string(), out.string(), "--backend", "cpu", "--frames", "8",
                                "--no-preview"}) == 0);
  const auto before = test::snapshot(out);
  // Frame 4's header reads, its pixel data is cut short: only the read stage finds it, while
  // the frames before it are being denoised and written.
  const fs::path frame4 = in / io::frame_file_name(4);
  fs::resize_file(frame4, fs::file_size(frame4) - 64);
  REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "cpu",
                                            "--frames", "8", "--no-verify"}),
                      Catch::Contains(frame4.string()));
  REQUIRE(test::snapshot(out) == before);
  REQUIRE(test::leftovers(out).empty());
  const auto report = read_json(out.string() + ".failed-report.json");
  REQUIRE(report["stage"] == "denoising");
  REQUIRE(report["frame"] == 4);
  REQUIRE(report["file"] == frame4.string());
  REQUIRE(report["frame_step"] == "read");
  REQUIRE(report["frames_written"] == 4);  // frames 0 to 3, whole, as one frame at a time
  REQUIRE_THAT(report["error"].get<std::string>(), Catch::Contains(frame4.string()));
  fs::remove_all(in);
  test::remove_output(out);
}

TEST_CASE("svgf denoise reports where a frame's wall time goes, and frames per second",
          "[app][pipeline]") {
  const fs::path out = scratch("timing_out");
  int status = -1;
  const std::string printed =
      run_binary("denoise " + kCut.string() + " " + out.string() +
                     " --backend cpu --threads 2 --frames 4 --no-preview",
                 status);
  INFO(printed);
  REQUIRE(status == 0);
  CHECK_THAT(printed, Catch::Contains("fps") && Catch::Contains("stages per frame  read ") &&
                          Catch::Contains(" + denoise ") && Catch::Contains(" + write ") &&
                          Catch::Contains("with 3 frames in flight"));
  const auto report = read_json(out / "report.json");
  REQUIRE(report.contains("timing"));
  const auto& t = report["timing"];
  REQUIRE(t["frames_in_flight"] == 3);
  for (const char* key : {"median_read_ms", "median_denoise_ms", "median_write_ms",
                          "stage_sum_ms_per_frame", "wall_ms_per_frame", "speedup_over_stage_sum"}) {
    INFO(key);
    REQUIRE(t[key].get<double>() > 0);
  }
  for (const auto& f : report["frames"])
    for (const char* key : {"read_ms", "time_ms", "write_ms"}) REQUIRE(f[key].get<double>() > 0);
  REQUIRE_THAT(file_bytes(out / "report.html"), Catch::Contains("Where a frame&#39;s wall time goes") ||
                                                    Catch::Contains("Where a frame's wall time goes"));
  REQUIRE_THROWS_AS(app::denoise_command({kCut.string(), out.string(), "--frames-in-flight", "4"}),
                    app::UsageError);
  test::remove_output(out);
}
