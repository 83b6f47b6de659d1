#include "gbuffer/eval_set.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "gbuffer/eval_record.h"
#include "gbuffer/fixture_format.h"
#include "gbuffer/scene_timeline.h"
#include "gbuffer/scenes.h"
#include "io/exr_frame.h"
#include "io/sequence.h"
#include "io/sha256.h"

namespace fs = std::filesystem;

namespace svgf::gbuffer {

namespace {

EvalRecord wanted_record(const EvalSequence& seq, const EvalParams& p) {
  EvalRecord r;
  r.scene = seq.scene.name;
  r.generator = generator_tag();
  r.width = p.width;
  r.height = p.height;
  r.frames = p.frames;
  r.spp = p.spp;
  r.reference_spp = p.reference_spp;
  r.seed = p.seed;
  r.split = seq.settings.split;
  r.gradients = seq.settings.gradients;
  r.sha256.assign(static_cast<size_t>(p.frames), "");
  r.reference_noise.assign(static_cast<size_t>(p.frames), ReferenceNoise{});
  return r;
}

std::string frame_path(const EvalSequence& seq, int k) {
  return (fs::path(seq.dir) / io::frame_file_name(k)).string();
}

bool is_frame_file(const std::string& name) {
  return name.size() == 14 && name.compare(0, 6, "frame_") == 0 &&
         name.compare(10, 4, ".exr") == 0 &&
         name.find_first_not_of("0123456789", 6) == 10;
}

// A file this code writes, or the temporary name it writes it under (io/atomic_file.h).
bool is_sequence_file(const std::string& name, bool temporary) {
  const size_t tmp = name.find(".tmp-");
  if ((tmp != std::string::npos) != temporary) return false;
  const std::string base = temporary ? name.substr(0, tmp) : name;
  return is_frame_file(base) || base == "eval.json" || base == "manifest.json";
}

void remove_files(const std::string& dir, bool temporary) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && is_sequence_file(e.path().filename().string(), temporary))
      fs::remove(e.path());
}

// An exclusive flock on <dir>/.lock for the object's life.
class FolderLock {
 public:
  explicit FolderLock(const std::string& dir) {
    const std::string path = (fs::path(dir) / ".lock").string();
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw std::runtime_error(path + ": cannot open: " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      throw std::runtime_error(dir + " is being rendered by another process (it holds " + path +
                               ")");
    }
  }
  ~FolderLock() { ::close(fd_); }  // closing releases the lock
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

io::Manifest manifest_of(const EvalSequence& seq, const EvalRecord& r) {
  io::Manifest m;
  m.scene = r.scene;
  m.width = r.width;
  m.height = r.height;
  m.spp = r.spp;
  m.reference_spp = r.reference_spp;
  m.seed = r.seed;
  m.generator = r.generator;
  for (int k = 0; k < r.frames; ++k)
    m.frames.push_back({io::frame_file_name(k), r.sha256[static_cast<size_t>(k)]});
  for (int c : seq.scene.camera_cuts)
    if (c > 0 && c < r.frames) m.camera_cuts.push_back(c);
  return m;
}

bool same_manifest(const io::Manifest& a, const io::Manifest& b) {
  if (a.frames.size() != b.frames.size()) return false;
  for (size_t k = 0; k < a.frames.size(); ++k)
    if (a.frames[k].name != b.frames[k].name || a.frames[k].sha256 != b.frames[k].sha256)
      return false;
  return a.scene == b.scene && a.width == b.width && a.height == b.height && a.spp == b.spp &&
         a.reference_spp == b.reference_spp && a.seed == b.seed && a.generator == b.generator &&
         a.camera_cuts == b.camera_cuts;
}

// Writes manifest.json unless the folder already has this one (a reused sequence stays as it is).
void write_manifest_if_changed(const std::string& dir, const io::Manifest& m) {
  if (fs::exists(fs::path(dir) / "manifest.json")) {
    try {
      if (same_manifest(io::read_manifest(dir), m)) return;
    } catch (const std::exception&) {
      // unreadable: written again below
    }
  }
  io::write_manifest(dir, m);
}

}  // namespace

std::vector<std::string> eval_scene_names() {
  std::vector<std::string> names;
  for (const SceneDesc& s : scene_library()) names.push_back(s.name);
  return names;
}

std::string default_eval_dir() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && xdg[0] == '/') return (fs::path(xdg) / "svgf" / "eval").string();
  const char* home = std::getenv("HOME");
  if (home && home[0] == '/') return (fs::path(home) / ".cache" / "svgf" / "eval").string();
  return "svgf-eval-cache";
}

EvalSequence eval_sequence(const std::string& root, const std::string& scene_name,
                           const EvalParams& p) {
  EvalSequence seq;
  seq.scene = scene_over(find_scene(scene_name), p.frames);
  seq.settings.width = p.width;
  seq.settings.height = p.height;
  seq.settings.spp = p.spp;
  seq.settings.reference_spp = p.reference_spp;
  seq.settings.seed = p.seed;
  seq.settings.split = p.split;
  seq.settings.gradients = seq.scene.gradients;  // as the scene's committed fixture
  validate(seq.settings);
  seq.dir = (fs::path(root) / scene_name).string();
  return seq;
}

EvalPlan plan_eval_sequence(const EvalSequence& seq, const EvalParams& p) {
  EvalPlan plan;
  const std::string& name = seq.scene.name;
  const EvalRecord wanted = wanted_record(seq, p);
  std::optional<EvalRecord> cached;
  try {
    cached = read_eval_record(seq.dir);
  } catch (const std::exception& e) {
    plan.notes.push_back(name + ": rendering all " + std::to_string(p.frames) + " frames: " +
                         e.what());
  }
  if (cached) {
    const std::vector<std::string> diffs = parameter_differences(*cached, wanted);
    if (!diffs.empty()) {
      std::string why;
      for (const std::string& d : diffs) why += (why.empty() ? "" : "; ") + d;
      plan.notes.push_back(name + ": rendering all " + std::to_string(p.frames) +
                           " frames again: " + why);
      cached.reset();
    }
  } else if (plan.notes.empty() && fs::is_directory(seq.dir)) {
    for (const auto& e : fs::directory_iterator(seq.dir))
      if (is_sequence_file(e.path().filename().string(), false)) {
        plan.notes.push_back(name + ": rendering all " + std::to_string(p.frames) +
                             " frames: " + seq.dir + " has sequence files but no eval.json");
        break;
      }
  }
  if (!cached) {
    plan.restart = true;
    for (int k = 0; k < p.frames; ++k) plan.to_render.push_back(k);
    return plan;
  }
  for (int k = 0; k < p.frames; ++k) {
    const std::string path = frame_path(seq, k);
    const std::string& recorded = cached->sha256[static_cast<size_t>(k)];
    const bool exists = fs::exists(path);
    std::string problem;
    if (exists && recorded.empty())
      problem = "not in eval.json (a run stopped while writing it)";
    else if (!exists && !recorded.empty())
      problem = "missing";
    else if (exists && io::sha256_file(path) != recorded)
      problem = "its SHA-256 differs from eval.json's";
    else if (exists && p.reference_spp >= 2 && !cached->records_reference_noise)
      problem = "no reference noise in eval.json (rendered before it was recorded)";
    if (exists && problem.empty()) {
      ++plan.kept;
      continue;
    }
    plan.to_render.push_back(k);
    if (!problem.empty())
      plan.notes.push_back(name + ": " + path + ": " + problem + ": rendering it again");
  }
  return plan;
}

void render_eval_sequence(const Renderer& renderer, const EvalSequence& seq, const EvalParams& p,
                          const EvalPlan& plan, RenderCounters* counters,
                          const std::function<void(int)>& on_frame) {
  fs::create_directories(seq.dir);
  const FolderLock lock(seq.dir);
  remove_files(seq.dir, /*temporary=*/true);  // left by a killed run: nobody else writes here
  EvalRecord record = wanted_record(seq, p);
  if (plan.restart) {
    remove_files(seq.dir, /*temporary=*/false);
  } else {
    // Read again under the lock: the plan's hashes are kept only where the record still agrees.
    const std::optional<EvalRecord> cached = read_eval_record(seq.dir);
    if (!cached || !parameter_differences(*cached, record).empty())
      throw std::runtime_error(seq.dir + ": eval.json changed since it was read; run again");
    record.sha256 = cached->sha256;
    record.reference_noise = cached->reference_noise;
  }
  if (!plan.to_render.empty()) {
    fs::remove(fs::path(seq.dir) / "manifest.json");  // the sequence is incomplete until the end
    for (int k : plan.to_render) {
      record.sha256[static_cast<size_t>(k)].clear();
      record.reference_noise[static_cast<size_t>(k)] = ReferenceNoise{};
    }
    write_eval_record(seq.dir, record);
  }
  for (int k : plan.to_render) {
    ReferenceNoise& noise = record.reference_noise[static_cast<size_t>(k)];
    const Frame f = renderer.render(seq.scene, k, seq.settings, counters, &noise);
    const std::string path = frame_path(seq, k);
    io::write_frame(path, f, fixture_storage());  // a temporary name, then renamed
    record.sha256[static_cast<size_t>(k)] = io::sha256_file(path);
    write_eval_record(seq.dir, record);
    if (on_frame) on_frame(k);
  }
  if (!record.complete())
    throw std::logic_error(seq.dir + ": frames missing after rendering the plan");
  write_manifest_if_changed(seq.dir, manifest_of(seq, record));
}

}  // namespace svgf::gbuffer
