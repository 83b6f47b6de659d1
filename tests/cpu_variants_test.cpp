// The CPU kernels' instruction-set variants (kernels_cpu/cpu_variant.h): every variant gives the
// bits of the narrowest one for every method, the dispatch picks the widest this CPU runs, and a
// variant this CPU cannot run is refused by name. A variant this CPU cannot run is reported as
// skipped (ctest: SKIP_REGULAR_EXPRESSION "SKIPPED:"), never as passed. That the variants share
// no code is checked on the archive (svgf_cpu_variants_isolated, kernels_cpu/
// check_variant_isolation.cmake).
#include <cstdlib>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "io/sequence.h"
#include "kernels_cpu/cpu_variant.h"
#include "pipeline/make_denoiser.h"
#include "synthetic_sequence.h"
#include "test_support.h"

using namespace svgf;
using Catch::Contains;

namespace {

// The configurations compared: each method at its defaults (SVGF's first frames run the spatial
// variance, later ones the temporal), the JBF in both forms, SVGF with a normal power outside
// the compiled-in ones.
std::vector<std::pair<std::string, DenoiserConfig>> configurations() {
  std::vector<std::pair<std::string, DenoiserConfig>> c;
  for (Method m : {Method::Svgf, Method::Gaussian, Method::Wavelet, Method::Jbf,
                   Method::JbfAtrous, Method::Bmfr}) {
    DenoiserConfig config;
    config.method = m;
    config.threads = 2;
    config.jbf.radius = 5;  // the full window's rows at a test's cost (16: 11x the taps)
    c.emplace_back(to_string(m), config);
  }
  DenoiserConfig odd_power;
  odd_power.svgf.phi_normal = 100.f;
  odd_power.threads = 2;
  c.emplace_back("svgf phi_normal 100", odd_power);
  return c;
}

// Two short sequences: the first 4 frames of a committed fixture (128x128), and a generated
// one whose width is no multiple of any vector width (the rows' tails).
std::vector<std::pair<std::string, std::vector<Frame>>> sequences() {
  std::vector<std::pair<std::string, std::vector<Frame>>> s;
  const io::Sequence fixture(std::string(SVGF_SOURCE_DIR) + "/fixtures/camera-pan");
  std::vector<Frame> pan;
  for (int k = 0; k < 4; ++k) pan.push_back(fixture.read(k));
  s.emplace_back("camera-pan", std::move(pan));
  test::SyntheticScene scene;
  scene.width = 67;
  scene.height = 29;
  std::vector<Frame> moving;
  for (int k = 0; k < 4; ++k) moving.push_back(scene.frame(k));
  s.emplace_back("synthetic 67x29", std::move(moving));
  return s;
}

// Every output frame of every configuration on every sequence, on variant `id`.
std::vector<Image> outputs(const std::string& id,
                           const std::vector<std::pair<std::string, std::vector<Frame>>>& seqs,
                           std::vector<std::string>* labels = nullptr) {
  std::vector<Image> out;
  for (auto [name, config] : configurations()) {
    config.cpu_isa = id;
    for (const auto& [seq_name, frames] : seqs) {
      auto denoiser = make_denoiser(config);
      REQUIRE_THAT(denoiser->description(), Contains(cpu::pick_variant(id).name));
      for (size_t k = 0; k < frames.size(); ++k) {
        out.emplace_back();
        denoiser->denoise(frames[k], out.back());
        if (labels) labels->push_back(name + " on " + seq_name + ", frame " + std::to_string(k));
      }
    }
  }
  return out;
}

const cpu::CpuVariant* built(const std::string& id) {
  for (const cpu::CpuVariant* v : cpu::built_variants())
    if (id == v->id) return v;
  return nullptr;
}

// The narrowest built variant this CPU runs: what the others are compared with.
const cpu::CpuVariant* reference_variant() {
  for (const cpu::CpuVariant* v : cpu::built_variants())
    if (cpu::runs_here(*v)) return v;
  return nullptr;
}

// One test body for every variant: its outputs equal the reference variant's bit for bit.
void check_same_bits_as_reference(const std::string& id) {
  const cpu::CpuVariant* v = built(id);
  const cpu::CpuVariant* ref = reference_variant();
  std::string why;
  if (v == nullptr) {
    WARN("SKIPPED: x86-64-" << id << " variant not run: this build does not have it (SVGF_CPU_ISAS)");
    return;
  }
  if (!cpu::runs_here(*v, &why)) {
    WARN("SKIPPED: " << v->name << " variant not run: " << why);
    return;
  }
  if (ref == nullptr || ref == v) {
    WARN("SKIPPED: " << v->name << " is the narrowest variant this CPU runs: nothing to compare with");
    return;
  }
  const auto seqs = sequences();
  std::vector<std::string> labels;
  const std::vector<Image> expected = outputs(ref->id, seqs, &labels);
  const std::vector<Image> got = outputs(v->id, seqs);
  REQUIRE(got.size() == expected.size());
  for (size_t i = 0; i < got.size(); ++i)
    test::require_identical(got[i], expected[i],
                            std::string(v->name) + " vs " + ref->name + ": " + labels[i]);
}

// The widest level this CPU has, found here with the compiler's checks (independently of
// kernels_cpu/cpu_variant.cpp's tables).
std::string widest_level_here() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl"))
    return "v4";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
      __builtin_cpu_supports("bmi2"))
    return "v3";
  if (__builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("popcnt")) return "v2";
  return "";
}

// Sets an environment variable for the scope of a test.
struct ScopedEnv {
  ScopedEnv(const char* name, const char* value) : name_(name) { setenv(name, value, 1); }
  ~ScopedEnv() { unsetenv(name_); }
  const char* name_;
};

}  // namespace

TEST_CASE("cpu variants: x86-64-v3 gives the bits of the narrowest variant", "[cpu_variants]") {
  check_same_bits_as_reference("v3");
}

TEST_CASE("cpu variants: x86-64-v4 gives the bits of the narrowest variant", "[cpu_variants]") {
  check_same_bits_as_reference("v4");
}

TEST_CASE("cpu variants: auto picks the widest built variant this CPU runs", "[cpu_variants]") {
  unsetenv("SVGF_CPU_ISA");
  if (built("custom") != nullptr) {
    WARN("SKIPPED: a build with SVGF_CPU_ARCH_FLAGS has one variant, custom");
    return;
  }
  const std::string widest = widest_level_here();
  std::string expected;
  for (const cpu::CpuVariant* v : cpu::built_variants())
    if (std::string(v->id) <= widest) expected = v->id;  // "v2" < "v3" < "v4"
  INFO("this CPU's widest level: x86-64-" << widest);
  REQUIRE_FALSE(expected.empty());
  CHECK(cpu::pick_variant("auto").id == expected);
  CHECK(cpu::pick_variant("").id == expected);
  DenoiserConfig config;
  REQUIRE_THAT(make_denoiser(config)->description(), Contains("x86-64-" + expected));
}

TEST_CASE("cpu variants: SVGF_CPU_ISA picks one, EngineConfig::cpu_isa wins over it",
          "[cpu_variants]") {
  const cpu::CpuVariant* narrowest = reference_variant();
  REQUIRE(narrowest != nullptr);
  const ScopedEnv env("SVGF_CPU_ISA", narrowest->id);
  CHECK(&cpu::pick_variant("") == narrowest);
  DenoiserConfig config;
  config.method = Method::Gaussian;
  CHECK_THAT(make_denoiser(config)->description(), Contains(narrowest->name));
  config.cpu_isa = "auto";
  const cpu::CpuVariant& widest = cpu::pick_variant("auto");
  CHECK_THAT(make_denoiser(config)->description(), Contains(widest.name));
}

TEST_CASE("cpu variants: an unknown name is a usage error naming the known ones",
          "[cpu_variants]") {
  unsetenv("SVGF_CPU_ISA");
  CHECK_THROWS_AS(cpu::pick_variant("v5"), std::invalid_argument);
  CHECK_THROWS_WITH(cpu::pick_variant("v5"),
                    Contains("cpu_isa=v5: unknown CPU kernel variant (known: auto, "));
  const ScopedEnv env("SVGF_CPU_ISA", "avx9");
  DenoiserConfig config;
  CHECK_THROWS_AS(make_denoiser(config), std::invalid_argument);
  CHECK_THROWS_WITH(make_denoiser(config), Contains("SVGF_CPU_ISA=avx9: unknown"));
}

TEST_CASE("cpu variants: a variant this CPU lacks is refused, naming the missing features",
          "[cpu_variants]") {
  unsetenv("SVGF_CPU_ISA");
  int refused = 0;
  for (const cpu::CpuVariant* v : cpu::built_variants()) {
    if (cpu::runs_here(*v)) continue;
    DenoiserConfig config;
    config.cpu_isa = v->id;
    INFO(v->name);
    CHECK_THROWS_AS(make_denoiser(config), std::runtime_error);
    CHECK_THROWS_WITH(make_denoiser(config),
                      Contains(std::string("cpu_isa=") + v->id + ": the " + v->name +
                               " CPU kernels cannot run here: this CPU lacks "));
    ++refused;
  }
  if (refused == 0) WARN("SKIPPED: this CPU runs every variant of this build: none to refuse");
}
