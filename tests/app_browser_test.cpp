// report.html in a real browser: headless Chromium (Debian's chromium package) opens the report
// of a 3-frame run of a committed fixture at its third frame (report.html#frame=2). The page's
// script must have run (--dump-dom: every image decoded, the plots' points parsed, frame 2
// selected) and the screenshot must show frame 2's images pixel for pixel where the page put
// them, side by side above the plots, and the plots' lines. Hidden ([.browser]): ctest runs it as
// svgf_app_tests:browser, reported Skipped where no browser is installed ($SVGF_BROWSER names
// one elsewhere).
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "app/denoise_command.h"
#include "app/html_report.h"
#include "io/png.h"
#include "app_test_support.h"
#include "html_page_support.h"

namespace fs = std::filesystem;
using namespace svgf;

namespace {

constexpr int kWindowWidth = 1200, kWindowHeight = 1400;

// $SVGF_BROWSER, else the first Chromium on the PATH; empty when none (`looked` says where).
std::string find_browser(std::string* looked) {
  if (const char* named = std::getenv("SVGF_BROWSER"); named && *named) return named;
  const char* path = std::getenv("PATH");
  *looked = "chromium, chromium-browser, google-chrome in PATH";
  for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
    std::istringstream dirs(path ? path : "");
    for (std::string dir; std::getline(dirs, dir, ':');)
      if (!dir.empty() && ::access((fs::path(dir) / name).c_str(), X_OK) == 0)
        return (fs::path(dir) / name).string();
  }
  return "";
}

std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Runs the browser headless on `url` with `action` (--screenshot=FILE or --dump-dom), stdout
// into `out`, stderr into `log`. --no-sandbox: Debian's chromium refuses to run as root without.
// --virtual-time-budget: the page's promises (image decoding) settle before the capture.
int run_browser(const std::string& browser, const fs::path& profile, const std::string& action,
                const std::string& url, const fs::path& out, const fs::path& log) {
  const std::string command =
      "timeout 60 " + quoted(browser) +
      " --headless --disable-gpu --no-sandbox --hide-scrollbars --force-device-scale-factor=1"
      " --no-first-run --virtual-time-budget=5000 --user-data-dir=" +
      quoted(profile.string()) + " --window-size=" + std::to_string(kWindowWidth) + "," +
      std::to_string(kWindowHeight) + " " + action + " " + quoted(url) + " >" +
      quoted(out.string()) + " 2>" + quoted(log.string());
  return std::system(command.c_str());
}

struct Rect {
  int x = 0, y = 0, w = 0, h = 0;
};
Rect rect_of(const std::string& tag) {
  Rect r;
  char comma;
  std::istringstream in(test::attribute(tag, "data-rect"));
  in >> r.x >> comma >> r.y >> comma >> r.w >> comma >> r.h;
  if (!in) FAIL("no data-rect in " << tag.substr(0, 120));
  return r;
}

const uint8_t* pixel(const io::Rgb8Image& im, int x, int y) {
  return &im.rgb[(static_cast<size_t>(y) * im.width + x) * 3];
}

}  // namespace

TEST_CASE("report.html renders in headless Chromium: images, plots, script", "[.browser]") {
  std::string looked;
  const std::string browser = find_browser(&looked);
  if (browser.empty()) {
    WARN("SKIPPED: no browser to render report.html (looked for "
         << looked << "; apt-get install chromium, or set SVGF_BROWSER)");
    return;
  }
  const fs::path out = test::scratch("browser_out"), work = test::scratch("browser_work");
  fs::create_directories(work);
  REQUIRE(app::denoise_command({std::string(SVGF_SOURCE_DIR) + "/fixtures/cornell-static",
                                out.string(), "--frames", "3", "--backend", "cpu"}) == 0);
  const std::string url = "file://" + fs::absolute(out / app::kReportHtml).string() + "#frame=2";
  const fs::path shot = work / "shot.png", dom = work / "dom.html", log = work / "browser.log";
  INFO(browser << "; its messages are in " << log);
  REQUIRE(run_browser(browser, work / "profile", "--dump-dom", url, dom, log) == 0);
  REQUIRE(run_browser(browser, work / "profile", "--screenshot=" + shot.string(), url,
                      work / "stdout", log) == 0);

  // The script ran: every image decoded, frame 2 selected, the plots' points parsed.
  const std::string page = test::file_bytes(dom);
  const auto body = test::tags(page, "body");
  REQUIRE(body.size() == 1);
  REQUIRE(test::attribute(body[0], "data-ready") == "1");
  CHECK(test::attribute(body[0], "data-images-decoded") == "12");  // 3 frames x 4 images
  CHECK(test::attribute(body[0], "data-images-failed") == "0");
  CHECK(test::attribute(body[0], "data-frame") == "2");
  const auto report = test::read_json(out / "report.json");
  const size_t stages = report["frames"][0]["stage_ms"].size();
  const auto plots = test::tags(page, "svg class=\"plot\"");
  REQUIRE(plots.size() == 3);  // PSNR and relMSE (noisy, denoised), time (frame and each stage)
  CHECK(test::attribute(plots[0], "data-parsed-points") == "6");
  CHECK(test::attribute(plots[1], "data-parsed-points") == "6");
  CHECK(test::attribute(plots[2], "data-parsed-points") == std::to_string(3 * (1 + stages)));

  // The screenshot: not blank, frame 2's four images side by side exactly as embedded, the plots
  // below them with their lines drawn.
  const io::Rgb8Image screen = io::decode_png_rgb8(test::file_bytes(shot), shot.string());
  REQUIRE(screen.width == kWindowWidth);
  REQUIRE(screen.height == kWindowHeight);
  std::set<uint32_t> colours;
  for (size_t i = 0; i < screen.rgb.size(); i += 3)
    colours.insert(uint32_t(screen.rgb[i]) << 16 | uint32_t(screen.rgb[i + 1]) << 8 |
                   screen.rgb[i + 2]);
  CHECK(colours.size() > 2000);

  std::vector<std::string> shown;  // the images the script placed (frame 2's only)
  for (const std::string& img : test::frame_images(page))
    if (test::has_attribute(img, "data-rect")) shown.push_back(img);
  REQUIRE(shown.size() == 4);
  const auto all = test::frame_images(page);
  CHECK(test::attribute(shown[0], "src") == test::attribute(all[8], "src"));  // frame 2's noisy
  CHECK(test::attribute(all[0], "src") != test::attribute(all[8], "src"));    // not frame 0's
  int right_edge = 0, images_bottom = 0;
  for (const std::string& img : shown) {
    INFO(test::attribute(img, "data-name"));
    const Rect r = rect_of(img);
    const io::Rgb8Image want = test::image_of_src(test::attribute(img, "src"));
    REQUIRE(r.w == want.width);  // shown 1:1
    REQUIRE(r.h == want.height);
    REQUIRE(r.x + r.w <= screen.width);
    REQUIRE(r.y + r.h <= screen.height);
    CHECK(r.y == rect_of(shown[0]).y);  // side by side
    CHECK(r.x >= right_edge);
    right_edge = r.x + r.w;
    images_bottom = r.y + r.h;
    int off = 0;
    for (int y = 0; y < r.h; ++y)
      for (int x = 0; x < r.w; ++x)
        for (int c = 0; c < 3; ++c)
          off += std::abs(int(pixel(screen, r.x + x, r.y + y)[c]) - int(pixel(want, x, y)[c])) > 2;
    CHECK(off == 0);
  }
  for (const std::string& svg : plots) {
    INFO(test::attribute(svg, "aria-label"));
    const Rect r = rect_of(svg);
    CHECK(r.y > images_bottom);
    int line = 0;  // pixels of the first series' colour, #1f77b4
    for (int y = r.y; y < std::min(r.y + r.h, screen.height); ++y)
      for (int x = r.x; x < std::min(r.x + r.w, screen.width); ++x) {
        const uint8_t* p = pixel(screen, x, y);
        line += std::abs(p[0] - 0x1f) + std::abs(p[1] - 0x77) + std::abs(p[2] - 0xb4) < 40;
      }
    CHECK(line > 100);
  }
  fs::remove_all(work);
  test::remove_output(out);
}
