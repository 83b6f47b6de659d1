#include "app/method_options.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

namespace svgf::app {

const char* const kMethodParamUsage =
    "  --iterations N            svgf, wavelet: a-trous iterations (default 4)\n"
    "  --feedback-tap N          svgf: a-trous iteration fed back as history, -1 none (default 1)\n"
    "  --alpha A                 svgf: color temporal blend floor (default 0.05)\n"
    "  --moments-alpha A         svgf: moments temporal blend floor (default 0.2)\n"
    "  --phi-color X             svgf: luminance edge-stopping (default 10)\n"
    "  --history-cap N           svgf: longest history in frames (default 32)\n"
    "  --variance-of-mean on|off svgf: filter with the accumulated mean's variance (default off)\n"
    "  --antilag on|off          svgf: shorten a history its neighbourhood contradicts (default off)\n"
    "  --antilag-radius R        svgf: ... the (2R+1)^2 neighbourhood, R in 1..3 (default 2)\n"
    "  --antilag-low D           svgf: ... from D standard errors away (default 4)\n"
    "  --antilag-high D          svgf: ... all of it from D on (default 8)\n"
    "  --antilag-relative R      svgf: ... tolerance + R x luminance (default 0.05)\n"
    "  --svgf-preset NAME        svgf: default, falcor, paper or converge, set before the flags\n"
    "                            above (docs/svgf.md)\n"
    "  --phi-normal X            svgf: normal edge-stopping exponent (default 128)\n"
    "  --phi-depth X             svgf: depth edge-stopping, 0 = no depth term (default 1)\n"
    "  --sigma S                 gaussian: standard deviation in pixels (default 2)\n"
    "  --radius R                gaussian: taps either side, 0 = ceil(3 sigma) (default 0)\n"
    "  --kernel-size K           wavelet: taps per axis, 3, 5, 7 or 9 (default 5)\n"
    "  --sigma-depth S           wavelet: depth weight scale sigma_Z (default 1)\n"
    "  --sigma-normal S          wavelet: normal weight exponent sigma_N (default 64)\n"
    "  --sigma-luma S            wavelet: luma weight scale sigma_L (default 4)\n"
    "  --jbf-radius R            jbf: window radius in pixels (default 16)\n"
    "  --jbf-levels N            jbf-atrous: levels of 5x5 taps at 1, 2, 4, ... (default 4)\n"
    "  --jbf-sigma-coord S       jbf, jbf-atrous: pixel distance scale (default 32)\n"
    "  --jbf-sigma-color S       jbf, jbf-atrous: color distance scale (default 0.6)\n"
    "  --jbf-sigma-normal S      jbf, jbf-atrous: normal angle scale, radians (default 0.1)\n"
    "  --jbf-sigma-plane S       jbf, jbf-atrous: tangent-plane distance scale (default 0.1)\n"
    "  --jbf-alpha A             jbf, jbf-atrous: temporal blend, 1 = no history (default 0.2)\n"
    "  --jbf-clamp-k K           jbf, jbf-atrous: history clamp, mean +- K sigma (default 1)\n"
    "  --bmfr-rank S             bmfr: rank-deficient blocks: noise (the paper's) or skip (default noise)\n"
    "  --bmfr-noise A            bmfr: feature noise amplitude for noise (default 0.01)\n"
    "  --bmfr-skip-threshold T   bmfr: relative column norm under which skip drops it (default 0.001)\n"
    "  --bmfr-pre-alpha A        bmfr: noisy-color temporal blend floor (default 0.2)\n"
    "  --bmfr-post-alpha A       bmfr: output temporal blend floor (default 0.1)\n"
    "  --bmfr-position-limit D2  bmfr: squared world distance a history tap may lie at (default 0.01)\n"
    "  --bmfr-normal-limit D2    bmfr: squared normal difference a history tap may have (default 1)\n"
    "  --bmfr-taa on|off         bmfr: temporal anti-aliasing of the output (default off)\n"
    "  --bmfr-taa-alpha A        bmfr: its blend toward the new frame (default 0.2)\n";

namespace {

// Which methods read each flag (parse_method's names).
const std::map<std::string, std::vector<std::string>>& readers() {
  static const std::map<std::string, std::vector<std::string>> r = {
      {"iterations", {"svgf", "wavelet"}},
      {"feedback-tap", {"svgf"}},
      {"alpha", {"svgf"}},
      {"moments-alpha", {"svgf"}},
      {"phi-color", {"svgf"}},
      {"phi-normal", {"svgf"}},
      {"phi-depth", {"svgf"}},
      {"variance-of-mean", {"svgf"}},
      {"history-cap", {"svgf"}},
      {"svgf-preset", {"svgf"}},
      {"antilag", {"svgf"}},
      {"antilag-low", {"svgf"}},
      {"antilag-high", {"svgf"}},
      {"antilag-relative", {"svgf"}},
      {"antilag-radius", {"svgf"}},

      {"sigma", {"gaussian"}},
      {"radius", {"gaussian"}},
      {"kernel-size", {"wavelet"}},
      {"sigma-depth", {"wavelet"}},
      {"sigma-normal", {"wavelet"}},
      {"sigma-luma", {"wavelet"}},
      {"jbf-radius", {"jbf"}},
      {"jbf-levels", {"jbf-atrous"}},
      {"jbf-sigma-coord", {"jbf", "jbf-atrous"}},
      {"jbf-sigma-color", {"jbf", "jbf-atrous"}},
      {"jbf-sigma-normal", {"jbf", "jbf-atrous"}},
      {"jbf-sigma-plane", {"jbf", "jbf-atrous"}},
      {"jbf-alpha", {"jbf", "jbf-atrous"}},
      {"jbf-clamp-k", {"jbf", "jbf-atrous"}},
      {"bmfr-rank", {"bmfr"}},
      {"bmfr-noise", {"bmfr"}},
      {"bmfr-skip-threshold", {"bmfr"}},
      {"bmfr-pre-alpha", {"bmfr"}},
      {"bmfr-post-alpha", {"bmfr"}},
      {"bmfr-position-limit", {"bmfr"}},
      {"bmfr-normal-limit", {"bmfr"}},
      {"bmfr-taa", {"bmfr"}},
      {"bmfr-taa-alpha", {"bmfr"}}};
  return r;
}

}  // namespace

const std::set<std::string>& method_param_flags() {
  static const std::set<std::string> flags = [] {
    std::set<std::string> s;
    for (const auto& [flag, methods] : readers()) s.insert(flag);
    return s;
  }();
  return flags;
}

void read_method_params(const Options& o, DenoiserConfig& c) {
  SvgfParams& p = c.svgf;
  // A named configuration first; the single flags below change it.
  if (o.has("svgf-preset")) {
    try {
      p = svgf_preset(o.get("svgf-preset", "default"));
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  p.iterations = o.get_int("iterations", p.iterations, 0, 12);
  p.feedback_tap = o.get_int("feedback-tap", p.feedback_tap, -1, 11);
  p.alpha = o.get_float("alpha", p.alpha);
  p.moments_alpha = o.get_float("moments-alpha", p.moments_alpha);
  p.phi_color = o.get_float("phi-color", p.phi_color);
  p.phi_normal = o.get_float("phi-normal", p.phi_normal);
  p.phi_depth = o.get_float("phi-depth", p.phi_depth);
  p.antilag = o.get_on_off("antilag", p.antilag);
  p.antilag_low = o.get_float("antilag-low", p.antilag_low);
  p.antilag_high = o.get_float("antilag-high", p.antilag_high);
  p.antilag_relative = o.get_float("antilag-relative", p.antilag_relative);
  p.antilag_radius = o.get_int("antilag-radius", p.antilag_radius, 1, 3);
  p.history_cap = o.get_int("history-cap", p.history_cap, 1, 4096);
  p.variance_of_mean = o.get_on_off("variance-of-mean", p.variance_of_mean);
  GaussianParams& g = c.gaussian;
  g.sigma = o.get_float("sigma", g.sigma);
  g.radius = o.get_int("radius", g.radius, 0, 1024);
  WaveletParams& v = c.wavelet;
  v.iterations = o.get_int("iterations", v.iterations, 0, 12);
  v.kernel_size = o.get_int("kernel-size", v.kernel_size, 3, 9);
  v.sigma_depth = o.get_float("sigma-depth", v.sigma_depth);
  v.sigma_normal = o.get_float("sigma-normal", v.sigma_normal);
  v.sigma_luma = o.get_float("sigma-luma", v.sigma_luma);
  JbfParams& j = c.jbf;
  j.radius = o.get_int("jbf-radius", j.radius, 1, 64);
  j.levels = o.get_int("jbf-levels", c.method == Method::JbfAtrous ? 4 : 0, 0, 10);
  j.sigma_coord = o.get_float("jbf-sigma-coord", j.sigma_coord);
  j.sigma_color = o.get_float("jbf-sigma-color", j.sigma_color);
  j.sigma_normal = o.get_float("jbf-sigma-normal", j.sigma_normal);
  j.sigma_plane = o.get_float("jbf-sigma-plane", j.sigma_plane);
  j.alpha = o.get_float("jbf-alpha", j.alpha);
  j.clamp_k = o.get_float("jbf-clamp-k", j.clamp_k);
  BmfrParams& b = c.bmfr;
  b.noise_amount = o.get_float("bmfr-noise", b.noise_amount);
  b.skip_threshold = o.get_float("bmfr-skip-threshold", b.skip_threshold);
  b.pre_alpha = o.get_float("bmfr-pre-alpha", b.pre_alpha);
  b.post_alpha = o.get_float("bmfr-post-alpha", b.post_alpha);
  b.position_limit_sq = o.get_float("bmfr-position-limit", b.position_limit_sq);
  b.normal_limit_sq = o.get_float("bmfr-normal-limit", b.normal_limit_sq);
  b.taa_alpha = o.get_float("bmfr-taa-alpha", b.taa_alpha);
  b.taa = o.get_on_off("bmfr-taa", b.taa);
  try {
    b.rank_strategy = parse_bmfr_rank_strategy(o.get("bmfr-rank", to_string(b.rank_strategy)));
    b.validate();
    p.validate();
    g.validate();
    v.validate();
    j.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

void check_params_apply(const Options& o, const std::string& method) {
  for (const auto& [flag, methods] : readers()) {
    if (!o.has(flag)) continue;
    bool read = false;
    std::string list;
    for (const std::string& m : methods) {
      read = read || m == method;
      list += (list.empty() ? "" : ", ") + m;
    }
    if (!read)
      throw UsageError("--" + flag + " applies to " + list + ", not to " + method);
  }
}

}  // namespace svgf::app
