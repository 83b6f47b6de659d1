#include "bench/run_config.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace svgf::bench {
namespace {

using json = nlohmann::json;

// The method's parameters in a key: the ones a suite varies always, the rest only when they
// differ from the defaults (so every configuration has its own key, and the usual ones stay
// short).
std::string params_key(const DenoiserConfig& d) {
  std::ostringstream s;
  const auto unless_default = [&](const char* tag, float v, float fallback) {
    if (v != fallback) s << ' ' << tag << v;
  };
  switch (d.method) {
    case Method::Svgf: {
      const SvgfParams& p = d.svgf;
      const SvgfParams def;
      s << "it" << p.iterations << " tap" << p.feedback_tap;
      unless_default("a", p.alpha, def.alpha);
      unless_default("ma", p.moments_alpha, def.moments_alpha);
      unless_default("pc", p.phi_color, def.phi_color);
      unless_default("pn", p.phi_normal, def.phi_normal);
      unless_default("pd", p.phi_depth, def.phi_depth);
      unless_default("cap", static_cast<float>(p.history_cap), static_cast<float>(def.history_cap));
      if (p.variance_of_mean != def.variance_of_mean) s << (p.variance_of_mean ? " vom" : " novom");
      // The anti-lag's mode unless it is the default's (A-SVGF), then whatever of its
      // parameters is not the default's (gradient mode falls back to the statistics rule, so
      // both carry its thresholds).
      if (p.antilag != def.antilag) s << " antilag-" << to_string(p.antilag);
      if (p.antilag == Antilag::Gradient) {
        unless_default("gi", static_cast<float>(p.gradient_iterations),
                       static_cast<float>(def.gradient_iterations));
        unless_default("gpd", p.gradient_phi_depth, def.gradient_phi_depth);
        unless_default("gpn", p.gradient_phi_normal, def.gradient_phi_normal);
        unless_default("glr", static_cast<float>(p.gradient_lambda_radius),
                       static_cast<float>(def.gradient_lambda_radius));
      }
      if (p.antilag != Antilag::Off) {
        unless_default("al", p.antilag_low, def.antilag_low);
        unless_default("ah", p.antilag_high, def.antilag_high);
        unless_default("ar", p.antilag_relative, def.antilag_relative);
      }
      if (p.taa) s << " taa" << p.taa_alpha;
      if (p.split != def.split) s << " split-" << to_string(p.split);
      unless_default("iit", static_cast<float>(p.indirect_iterations),
                     static_cast<float>(def.indirect_iterations));
      unless_default("ipc", p.indirect_phi_color, def.indirect_phi_color);
      break;
    }
    case Method::Wavelet: {
      const WaveletParams& p = d.wavelet;
      const WaveletParams def;
      s << "it" << p.iterations << " k" << p.kernel_size;
      unless_default("sz", p.sigma_depth, def.sigma_depth);
      unless_default("sn", p.sigma_normal, def.sigma_normal);
      unless_default("sl", p.sigma_luma, def.sigma_luma);
      unless_default("eps", p.epsilon, def.epsilon);
      break;
    }
    case Method::Gaussian:
      s << "s" << d.gaussian.sigma;
      if (d.gaussian.radius > 0) s << " r" << d.gaussian.radius;
      break;
    case Method::Jbf:
    case Method::JbfAtrous: {
      const JbfParams& p = d.jbf;
      const JbfParams def;
      if (d.method == Method::Jbf) s << "r" << p.radius;
      else s << "l" << p.levels;
      unless_default("sp", p.sigma_coord, def.sigma_coord);
      unless_default("sc", p.sigma_color, def.sigma_color);
      unless_default("sn", p.sigma_normal, def.sigma_normal);
      unless_default("spl", p.sigma_plane, def.sigma_plane);
      unless_default("a", p.alpha, def.alpha);
      unless_default("k", p.clamp_k, def.clamp_k);
      break;
    }
    case Method::Bmfr: {
      const BmfrParams& p = d.bmfr;
      const BmfrParams def;
      s << to_string(p.rank_strategy);
      unless_default("n", p.noise_amount, def.noise_amount);
      unless_default("st", p.skip_threshold, def.skip_threshold);
      unless_default("a1", p.pre_alpha, def.pre_alpha);
      unless_default("a2", p.post_alpha, def.post_alpha);
      unless_default("pl", p.position_limit_sq, def.position_limit_sq);
      unless_default("nl", p.normal_limit_sq, def.normal_limit_sq);
      if (p.taa) s << " taa" << p.taa_alpha;
      break;
    }
  }
  return s.str();
}

json params_json(const DenoiserConfig& d) {
  switch (d.method) {
    case Method::Svgf: {
      const SvgfParams& p = d.svgf;
      return {{"iterations", p.iterations}, {"feedback_tap", p.feedback_tap},
              {"alpha", p.alpha},           {"moments_alpha", p.moments_alpha},
              {"phi_color", p.phi_color},   {"phi_normal", p.phi_normal},
              {"phi_depth", p.phi_depth},   {"history_cap", p.history_cap},
              {"variance_of_mean", p.variance_of_mean}, {"antilag", to_string(p.antilag)},
              {"antilag_low", p.antilag_low}, {"antilag_high", p.antilag_high},
              {"antilag_relative", p.antilag_relative},
              {"gradient_iterations", p.gradient_iterations},
              {"gradient_phi_depth", p.gradient_phi_depth},
              {"gradient_phi_normal", p.gradient_phi_normal},
              {"gradient_lambda_radius", p.gradient_lambda_radius},
              {"taa", p.taa}, {"taa_alpha", p.taa_alpha},
              {"split", to_string(p.split)},
              {"indirect_iterations", p.indirect_iterations},
              {"indirect_phi_color", p.indirect_phi_color}};
    }
    case Method::Wavelet: {
      const WaveletParams& p = d.wavelet;
      return {{"iterations", p.iterations},   {"kernel_size", p.kernel_size},
              {"sigma_depth", p.sigma_depth}, {"sigma_normal", p.sigma_normal},
              {"sigma_luma", p.sigma_luma},   {"epsilon", p.epsilon}};
    }
    case Method::Gaussian:
      return {{"sigma", d.gaussian.sigma}, {"radius", d.gaussian.radius}};
    case Method::Jbf:
    case Method::JbfAtrous: {
      const JbfParams& p = d.jbf;
      return {{"radius", p.radius},           {"levels", p.levels},
              {"sigma_coord", p.sigma_coord}, {"sigma_color", p.sigma_color},
              {"sigma_normal", p.sigma_normal}, {"sigma_plane", p.sigma_plane},
              {"alpha", p.alpha},             {"clamp_k", p.clamp_k}};
    }
    case Method::Bmfr: {
      const BmfrParams& p = d.bmfr;
      return {{"rank_strategy", to_string(p.rank_strategy)}, {"noise_amount", p.noise_amount},
              {"skip_threshold", p.skip_threshold},          {"pre_alpha", p.pre_alpha},
              {"post_alpha", p.post_alpha},                  {"position_limit_sq", p.position_limit_sq},
              {"normal_limit_sq", p.normal_limit_sq},        {"taa", p.taa},
              {"taa_alpha", p.taa_alpha}};
    }
  }
  return json::object();
}

}  // namespace

int RunConfig::resolved_threads() const {
  const int t = denoiser.threads;
  return t > 0 ? t : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

std::string RunConfig::key() const {
  if (method == "noisy") return "noisy input";
  if (!project()) return baseline.label();
  std::string k = method + " " + to_string(denoiser.backend) + " " + to_string(denoiser.mode) +
                  " " + params_key(denoiser);
  const DenoiserConfig defaults;
  if (cuda() && (denoiser.block_x != defaults.block_x || denoiser.block_y != defaults.block_y))
    k += " b" + std::to_string(denoiser.block_x) + "x" + std::to_string(denoiser.block_y);
  return k;
}

std::string RunConfig::label() const {
  const bool cpu_work = method != "noisy" && !cuda();
  return key() + (cpu_work ? " t" + std::to_string(resolved_threads()) : "");
}

RunConfig run_config(const std::string& method) {
  RunConfig c;
  c.method = method;
  if (is_baseline(method)) {
    c.baseline = baseline_by_name(method);
    return c;
  }
  try {
    c.denoiser.method = parse_method(method);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(e.what()) + "; OpenCV baselines: " + baseline_names());
  }
  return c;
}

RunConfig project_config(const std::string& method, Backend backend, Mode mode, int threads) {
  RunConfig c = run_config(method);
  c.denoiser.backend = backend;
  c.denoiser.mode = mode;
  c.denoiser.threads = threads;
  return c;
}

RunConfig svgf_config(Backend backend, Mode mode, int iterations, int feedback_tap, int threads) {
  RunConfig c = project_config("svgf", backend, mode, threads);
  c.denoiser.svgf.iterations = iterations;
  c.denoiser.svgf.feedback_tap = feedback_tap;
  return c;
}

std::vector<RunConfig> svgf_preset_configs(Backend backend, Mode mode, int threads) {
  std::vector<RunConfig> v;
  for (const char* name : {"paper", "falcor", "converge"}) {
    RunConfig c = project_config("svgf", backend, mode, threads);
    c.denoiser.svgf = svgf_preset(name);
    v.push_back(c);
  }
  // The defaults with the anti-lag rule frames without gradient samples run.
  RunConfig antilag = project_config("svgf", backend, mode, threads);
  antilag.denoiser.svgf.antilag = Antilag::Statistics;
  v.push_back(antilag);
  RunConfig taa = project_config("svgf", backend, mode, threads);  // the defaults + TAA
  taa.denoiser.svgf.taa = true;
  v.push_back(taa);
  return v;
}

RunConfig wavelet_config(Backend backend, Mode mode, int kernel_size, int threads) {
  RunConfig c = project_config("wavelet", backend, mode, threads);
  c.denoiser.wavelet.kernel_size = kernel_size;
  return c;
}

RunConfig jbf_config(Backend backend, Mode mode, int levels, int threads) {
  RunConfig c = project_config(levels > 0 ? "jbf-atrous" : "jbf", backend, mode, threads);
  c.denoiser.jbf.levels = levels;
  return c;
}

RunConfig bmfr_config(Backend backend, Mode mode, BmfrRankStrategy strategy, int threads) {
  RunConfig c = project_config("bmfr", backend, mode, threads);
  c.denoiser.bmfr.rank_strategy = strategy;
  return c;
}

RunConfig gaussian_config(Backend backend, Mode mode, float sigma, int radius, int threads) {
  RunConfig c = project_config("gaussian", backend, mode, threads);
  c.denoiser.gaussian.sigma = sigma;
  c.denoiser.gaussian.radius = radius;
  return c;
}

RunConfig baseline_config(const Baseline& b, int threads) {
  RunConfig c;
  c.method = b.name;
  c.baseline = b;
  c.denoiser.threads = threads;
  return c;
}

json config_json(const RunConfig& c) {
  json j;
  j["method"] = c.method;
  j["label"] = c.label();
  j["key"] = c.key();
  if (c.project()) {
    j["backend"] = to_string(c.denoiser.backend);
    j["mode"] = to_string(c.denoiser.mode);
    j.update(params_json(c.denoiser));
    if (c.cuda()) j["block"] = {c.denoiser.block_x, c.denoiser.block_y};
  } else if (c.method != "noisy") {
    j["backend"] = "cpu";
    j["mode"] = "opencv";
    j["params"] = {c.baseline.p1, c.baseline.p2, c.baseline.p3};
  }
  if (c.method != "noisy" && !c.cuda()) j["threads"] = c.resolved_threads();
  return j;
}

}  // namespace svgf::bench
