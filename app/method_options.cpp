#include "app/method_options.h"
#include "cli/command_line.h"

#include <stdexcept>
#include <type_traits>

namespace svgf::app {

namespace {

const char* const kGroup = "method parameters (a flag the method does not read is an error)";

// "svgf, wavelet: " before the help: which methods read the flag.
std::string help_of(const std::vector<std::string>& methods, const std::string& what) {
  std::string s;
  for (const std::string& m : methods) s += (s.empty() ? "" : ", ") + m;
  return s + ": " + what;
}

// The value type a setter (DenoiserConfig&, T) takes.
template <class F>
struct ValueOf : ValueOf<decltype(&F::operator())> {};
template <class C, class A, class T>
struct ValueOf<void (C::*)(A, T) const> {
  using type = std::decay_t<T>;
};

}  // namespace

void MethodParamFlags::add_to(CLI::App& app) {
  // One flag: read by `methods`, a T within its validator, applied by `set`.
  auto flag = [&](const std::string& name, const char* type, std::vector<std::string> methods,
                  const std::string& what, auto set) {
    using T = typename ValueOf<decltype(set)>::type;
    CLI::Option* o = app.add_option_function<T>(
        "--" + name,
        [this, set](const T& v) { given_.push_back([set, v](DenoiserConfig& c) { set(c, v); }); },
        help_of(methods, what));
    o->type_name(type)->group(kGroup);
    readers_.emplace_back(o, std::move(methods));
    return o;
  };
  const std::vector<std::string> svgf = {"svgf"}, jbfs = {"jbf", "jbf-atrous"}, bmfr = {"bmfr"};
  const CLI::Validator on_off(
      [](std::string& s) { return s == "on" || s == "off" ? "" : "must be on or off, got '" + s + "'"; },
      "");
  const CLI::Validator preset = cli::accepted_by([](const std::string& s) { svgf_preset(s); });
  CLI::Option* p = app.add_option("--svgf-preset", preset_,
                                  "svgf: default, falcor, paper or converge, set before the "
                                  "flags below (docs/svgf.md)");
  p->type_name("NAME")->group(kGroup)->check(preset);
  readers_.emplace_back(p, svgf);

  flag("iterations", "N", {"svgf", "wavelet"}, "a-trous iterations (default 4)",
       [](DenoiserConfig& c, int v) { c.svgf.iterations = c.wavelet.iterations = v; })
      ->check(CLI::Range(0, 12));
  flag("feedback-tap", "N", svgf, "a-trous iteration fed back as history, -1 none (default -1)",
       [](DenoiserConfig& c, int v) { c.svgf.feedback_tap = v; })
      ->check(CLI::Range(-1, 11));
  flag("alpha", "A", svgf, "color temporal blend floor (default 0.03)",
       [](DenoiserConfig& c, float v) { c.svgf.alpha = v; })->check(cli::NotNaN);
  flag("moments-alpha", "A", svgf, "moments temporal blend floor (default 0.2)",
       [](DenoiserConfig& c, float v) { c.svgf.moments_alpha = v; })->check(cli::NotNaN);
  flag("phi-color", "X", svgf, "luminance edge-stopping (default 4)",
       [](DenoiserConfig& c, float v) { c.svgf.phi_color = v; })->check(cli::NotNaN);
  flag("history-cap", "N", svgf, "longest history in frames (default 64)",
       [](DenoiserConfig& c, int v) { c.svgf.history_cap = v; })
      ->check(CLI::Range(1, 4096));
  flag("variance-of-mean", "on|off", svgf,
       "filter with the accumulated mean's variance (default on)",
       [](DenoiserConfig& c, bool v) { c.svgf.variance_of_mean = v; })->check(on_off);
  flag("camera-depth", "on|off", svgf,
       "reprojection: compare depths in the previous frame's camera (default on)",
       [](DenoiserConfig& c, bool v) { c.svgf.reproject_camera_depth = v; })->check(on_off);
  flag("svgf-taa", "on|off", svgf, "temporal anti-aliasing after remodulation (default off)",
       [](DenoiserConfig& c, bool v) { c.svgf.taa = v; })->check(on_off);
  flag("svgf-taa-alpha", "A", svgf, "its blend toward the new frame (default 0.1)",
       [](DenoiserConfig& c, float v) { c.svgf.taa_alpha = v; })->check(cli::NotNaN);
  const CLI::Validator antilag = cli::accepted_by([](const std::string& s) { parse_antilag(s); });
  flag("antilag", "MODE", svgf,
       "shorten a history the frame contradicts: off, statistics (alias on: its neighbourhood) or "
       "gradient (A-SVGF's gradient samples; statistics on frames without) (default gradient)",
       [](DenoiserConfig& c, const std::string& v) { c.svgf.antilag = parse_antilag(v); })
      ->check(antilag);
  flag("antilag-radius", "R", svgf, "... the (2R+1)^2 neighbourhood (default 2)",
       [](DenoiserConfig& c, int v) { c.svgf.antilag_radius = v; })
      ->check(CLI::Range(1, 3));
  flag("antilag-low", "D", svgf, "... from D standard errors away (default 4)",
       [](DenoiserConfig& c, float v) { c.svgf.antilag_low = v; })->check(cli::NotNaN);
  flag("antilag-high", "D", svgf, "... all of it from D on (default 8)",
       [](DenoiserConfig& c, float v) { c.svgf.antilag_high = v; })->check(cli::NotNaN);
  flag("antilag-relative", "R", svgf, "... tolerance + R x luminance (default 0.05)",
       [](DenoiserConfig& c, float v) { c.svgf.antilag_relative = v; })->check(cli::NotNaN);
  flag("gradient-iterations", "N", svgf, "A-SVGF: a-trous steps over the gradients (default 1)",
       [](DenoiserConfig& c, int v) { c.svgf.gradient_iterations = v; })
      ->check(CLI::Range(0, 8));
  flag("gradient-phi-depth", "X", svgf, "... their depth edge-stopping (default 1)",
       [](DenoiserConfig& c, float v) { c.svgf.gradient_phi_depth = v; })->check(cli::NotNaN);
  flag("gradient-phi-normal", "X", svgf, "... their normal exponent (default 128)",
       [](DenoiserConfig& c, float v) { c.svgf.gradient_phi_normal = v; })->check(cli::NotNaN);
  flag("gradient-lambda-radius", "R", svgf,
       "... a pixel takes the largest lambda of the (2R+1)^2 strata around its own (default 1)",
       [](DenoiserConfig& c, int v) { c.svgf.gradient_lambda_radius = v; })
      ->check(CLI::Range(0, 3));
  const CLI::Validator split = cli::accepted_by([](const std::string& s) { parse_split_mode(s); });
  flag("svgf-split", "auto|off|on", svgf,
       "filter direct and indirect apart, auto = when the frame carries both (default auto)",
       [](DenoiserConfig& c, const std::string& v) { c.svgf.split = parse_split_mode(v); })
      ->check(split);
  flag("indirect-iterations", "N", svgf, "... indirect's a-trous iterations, -1 = --iterations (default -1)",
       [](DenoiserConfig& c, int v) { c.svgf.indirect_iterations = v; })
      ->check(CLI::Range(-1, 12));
  flag("indirect-phi-color", "X", svgf, "... indirect's luminance edge-stopping, -1 = --phi-color (default -1)",
       [](DenoiserConfig& c, float v) { c.svgf.indirect_phi_color = v; })->check(cli::NotNaN);
  flag("phi-normal", "X", svgf, "normal edge-stopping exponent (default 128)",
       [](DenoiserConfig& c, float v) { c.svgf.phi_normal = v; })->check(cli::NotNaN);
  flag("phi-depth", "X", svgf, "depth edge-stopping, 0 = no depth term (default 1)",
       [](DenoiserConfig& c, float v) { c.svgf.phi_depth = v; })->check(cli::NotNaN);

  flag("sigma", "S", {"gaussian"}, "standard deviation in pixels (default 2)",
       [](DenoiserConfig& c, float v) { c.gaussian.sigma = v; })->check(cli::NotNaN);
  flag("radius", "R", {"gaussian"}, "taps either side, 0 = ceil(3 sigma) (default 0)",
       [](DenoiserConfig& c, int v) { c.gaussian.radius = v; })->check(CLI::Range(0, 1024));
  flag("kernel-size", "K", {"wavelet"}, "taps per axis, 3, 5, 7 or 9 (default 5)",
       [](DenoiserConfig& c, int v) { c.wavelet.kernel_size = v; })->check(CLI::Range(3, 9));
  flag("sigma-depth", "S", {"wavelet"}, "depth weight scale sigma_Z (default 1)",
       [](DenoiserConfig& c, float v) { c.wavelet.sigma_depth = v; })->check(cli::NotNaN);
  flag("sigma-normal", "S", {"wavelet"}, "normal weight exponent sigma_N (default 64)",
       [](DenoiserConfig& c, float v) { c.wavelet.sigma_normal = v; })->check(cli::NotNaN);
  flag("sigma-luma", "S", {"wavelet"}, "luma weight scale sigma_L (default 4)",
       [](DenoiserConfig& c, float v) { c.wavelet.sigma_luma = v; })->check(cli::NotNaN);

  flag("jbf-radius", "R", {"jbf"}, "window radius in pixels (default 16)",
       [](DenoiserConfig& c, int v) { c.jbf.radius = v; })->check(CLI::Range(1, 64));
  flag("jbf-levels", "N", {"jbf-atrous"}, "levels of 5x5 taps at 1, 2, 4, ... (default 4)",
       [](DenoiserConfig& c, int v) { c.jbf.levels = v; })->check(CLI::Range(0, 10));
  flag("jbf-sigma-coord", "S", jbfs, "pixel distance scale (default 32)",
       [](DenoiserConfig& c, float v) { c.jbf.sigma_coord = v; })->check(cli::NotNaN);
  flag("jbf-sigma-color", "S", jbfs, "color distance scale (default 0.6)",
       [](DenoiserConfig& c, float v) { c.jbf.sigma_color = v; })->check(cli::NotNaN);
  flag("jbf-sigma-normal", "S", jbfs, "normal angle scale, radians (default 0.1)",
       [](DenoiserConfig& c, float v) { c.jbf.sigma_normal = v; })->check(cli::NotNaN);
  flag("jbf-sigma-plane", "S", jbfs, "tangent-plane distance scale (default 0.1)",
       [](DenoiserConfig& c, float v) { c.jbf.sigma_plane = v; })->check(cli::NotNaN);
  flag("jbf-alpha", "A", jbfs, "temporal blend, 1 = no history (default 0.2)",
       [](DenoiserConfig& c, float v) { c.jbf.alpha = v; })->check(cli::NotNaN);
  flag("jbf-clamp-k", "K", jbfs, "history clamp, mean +- K sigma (default 1)",
       [](DenoiserConfig& c, float v) { c.jbf.clamp_k = v; })->check(cli::NotNaN);

  const CLI::Validator rank =
      cli::accepted_by([](const std::string& s) { parse_bmfr_rank_strategy(s); });
  flag("bmfr-rank", "S", bmfr, "rank-deficient blocks: noise (the paper's) or skip (default noise)",
       [](DenoiserConfig& c, const std::string& v) { c.bmfr.rank_strategy = parse_bmfr_rank_strategy(v); })
      ->check(rank);
  flag("bmfr-noise", "A", bmfr, "feature noise amplitude for noise (default 0.01)",
       [](DenoiserConfig& c, float v) { c.bmfr.noise_amount = v; })->check(cli::NotNaN);
  flag("bmfr-skip-threshold", "T", bmfr,
       "relative column norm under which skip drops it (default 0.001)",
       [](DenoiserConfig& c, float v) { c.bmfr.skip_threshold = v; })->check(cli::NotNaN);
  flag("bmfr-pre-alpha", "A", bmfr, "noisy-color temporal blend floor (default 0.2)",
       [](DenoiserConfig& c, float v) { c.bmfr.pre_alpha = v; })->check(cli::NotNaN);
  flag("bmfr-post-alpha", "A", bmfr, "output temporal blend floor (default 0.1)",
       [](DenoiserConfig& c, float v) { c.bmfr.post_alpha = v; })->check(cli::NotNaN);
  flag("bmfr-position-limit", "D2", bmfr,
       "squared world distance a history tap may lie at (default 0.01)",
       [](DenoiserConfig& c, float v) { c.bmfr.position_limit_sq = v; })->check(cli::NotNaN);
  flag("bmfr-normal-limit", "D2", bmfr,
       "squared normal difference a history tap may have (default 1)",
       [](DenoiserConfig& c, float v) { c.bmfr.normal_limit_sq = v; })->check(cli::NotNaN);
  flag("bmfr-taa", "on|off", bmfr, "temporal anti-aliasing of the output (default off)",
       [](DenoiserConfig& c, bool v) { c.bmfr.taa = v; })->check(on_off);
  flag("bmfr-taa-alpha", "A", bmfr, "its blend toward the new frame (default 0.2)",
       [](DenoiserConfig& c, float v) { c.bmfr.taa_alpha = v; })->check(cli::NotNaN);
}

void MethodParamFlags::check_apply(const std::string& method) const {
  for (const auto& [option, methods] : readers_) {
    if (option->count() == 0) continue;
    bool read = false;
    std::string list;
    for (const std::string& m : methods) {
      read = read || m == method;
      list += (list.empty() ? "" : ", ") + m;
    }
    if (!read) throw UsageError(option->get_name() + " applies to " + list + ", not to " + method);
  }
}

void MethodParamFlags::read(DenoiserConfig& c) const {
  // A named configuration first; the single flags change it.
  if (!preset_.empty()) c.svgf = svgf_preset(preset_);
  c.jbf.levels = c.method == Method::JbfAtrous ? 4 : 0;
  for (const auto& set : given_) set(c);
  try {
    c.bmfr.validate();
    c.svgf.validate();
    c.gaussian.validate();
    c.wavelet.validate();
    c.jbf.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace svgf::app
