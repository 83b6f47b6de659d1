// report.html: the page's structure (frames, embedded images, plot points, escaping), its
// images, and that svgf denoise and svgf compare write it. tests/app_browser_test.cpp renders it.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "app/compare_command.h"
#include "app/denoise_command.h"
#include "app/html_report.h"
#include "app/usage_error.h"
#include "app/report_images.h"
#include "core/tonemap.h"
#include "io/png.h"
#include "metrics/flip.h"
#include "app_test_support.h"
#include "html_page_support.h"

namespace fs = std::filesystem;
using namespace svgf;

namespace {

// A w x h image, pixel (x, y) of a colour of its own.
app::HtmlImage test_image(const std::string& name, int w, int h, int seed) {
  std::vector<uint8_t> rgb(static_cast<size_t>(w) * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<uint8_t>(i * 7 + seed * 31);
  return {name, io::encode_png_rgb8(rgb.data(), w, h)};
}

// Points of every polyline of an SVG plot, and its lone points (circles).
size_t plot_points(const std::string& svg) {
  size_t points = test::tags(svg, "circle").size();
  for (const std::string& line : test::tags(svg, "polyline")) {
    std::istringstream pairs(test::attribute(line, "points"));
    std::string pair;
    while (pairs >> pair) {
      REQUIRE(test::count_of(pair, ",") == 1);
      ++points;
    }
  }
  return points;
}

// The SVG plots of a page, each whole.
std::vector<std::string> plots_of(const std::string& html) {
  std::vector<std::string> plots;
  for (size_t at = html.find("<svg class=\"plot\""); at != std::string::npos;
       at = html.find("<svg class=\"plot\"", at + 1))
    plots.push_back(html.substr(at, html.find("</svg>", at) - at));
  return plots;
}

}  // namespace

TEST_CASE("base64 gives RFC 4648's test vectors", "[app][html]") {
  const std::vector<std::pair<std::string, std::string>> vectors = {{"", ""},
                                                                    {"f", "Zg=="},
                                                                    {"fo", "Zm8="},
                                                                    {"foo", "Zm9v"},
                                                                    {"foob", "Zm9vYg=="},
                                                                    {"fooba", "Zm9vYmE="},
                                                                    {"foobar", "Zm9vYmFy"}};
  for (const auto& [bytes, text] : vectors) {
    CHECK(app::base64(bytes) == text);
    CHECK(test::base64_decode(text) == bytes);
  }
  std::string all;
  for (int b = 0; b < 256; ++b) all += static_cast<char>(b);
  CHECK(test::base64_decode(app::base64(all)) == all);
}

TEST_CASE("html_report: frames, embedded images, plot points, escaping", "[app][html]") {
  app::HtmlReport r;
  r.title = "run <1> & \"two\"";
  r.frames = {"frame_0000.exr", "frame_0001.exr", "f</script><b>2"};
  r.plots.push_back({"PSNR (dB)", {{"noisy", {10, 11, 12}}, {"denoised", {30, 31, 32}}}, false});
  r.plots.push_back({"gaps", {{"a", {1, NAN, 3}}}, false});              // two lone points: dots
  r.plots.push_back({"relMSE", {{"b", {0.5, 0.05, -1}}}, true});         // log: -1 left out
  r.plots.push_back({"nothing", {{"c", {NAN, INFINITY, NAN}}}, false});  // not drawn
  r.images = {{test_image("noisy", 5, 4, 1), test_image("denoised", 5, 4, 2)},
              {},
              {test_image("noisy", 5, 4, 3), test_image("denoised", 5, 4, 4)}};
  r.images_note = "every other frame";
  r.tables.push_back(
      {"Configuration", {{"input", "<script>alert('x')</script>"}, {"a&b", "\"q\""}}});
  const std::string html = app::html_report(r);

  // One frame block each; images exactly as given, as base64 PNG data: URIs.
  const auto frames = test::tags(html, "div class=\"frame\"");
  REQUIRE(frames.size() == 3);
  CHECK_FALSE(test::has_attribute(frames[0], "hidden"));  // the first frame is shown at first
  CHECK(test::has_attribute(frames[1], "hidden"));
  const auto imgs = test::frame_images(html);
  REQUIRE(imgs.size() == 4);
  const size_t with_images[] = {0, 0, 2, 2};
  for (size_t i = 0; i < imgs.size(); ++i) {
    const app::HtmlImage& want = r.images[with_images[i]][i % 2];
    CHECK(test::attribute(imgs[i], "data-name") == want.name);
    const io::Rgb8Image got = test::image_of_src(test::attribute(imgs[i], "src"));
    CHECK(got.rgb == io::decode_png_rgb8(want.png, "given").rgb);
  }
  CHECK(test::count_of(html, "No images embedded for this frame") == 1);

  // Plots: one point per frame and series; gaps split the line; a plot with nothing drawable is
  // left out; non-positive values are left out of a log scale.
  const auto plots = plots_of(html);
  REQUIRE(plots.size() == 3);
  CHECK(plot_points(plots[0]) == 6);
  CHECK(test::tags(plots[0], "polyline").size() == 2);
  CHECK(plot_points(plots[1]) == 2);
  CHECK(test::tags(plots[1], "polyline").empty());
  CHECK(plot_points(plots[2]) == 2);
  CHECK(test::attribute(test::tags(plots[0], "svg")[0], "data-frames") == "3");
  CHECK(html.find("nothing") == std::string::npos);
  CHECK(html.find("log scale") != std::string::npos);

  // Escaped wherever text goes: no markup of the inputs survives, nor an early </script>.
  CHECK(html.find("<script>alert") == std::string::npos);
  CHECK(html.find("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;") != std::string::npos);
  CHECK(html.find("<th>a&amp;b</th><td>&quot;q&quot;</td>") != std::string::npos);
  CHECK(html.find("<title>run &lt;1&gt; &amp; &quot;two&quot;</title>") != std::string::npos);
  CHECK(html.find("f</script>") == std::string::npos);
  CHECK(test::count_of(html, "</script>") == 2);  // the data block and the script
  // Self-contained: nothing to fetch.
  CHECK(html.find("default-src 'none'") != std::string::npos);
  for (const char* fetch : {"src=\"http", "href=", "<link", "@import", "url("})
    CHECK(html.find(fetch) == std::string::npos);

  // A series that does not match the frames is the caller's bug.
  r.plots[0].series[0].values.pop_back();
  CHECK_THROWS_AS(app::html_report(r), std::invalid_argument);
}

TEST_CASE("html_frame_has_images: every frame up to the limit, then the limit spread evenly",
          "[app][html]") {
  auto count = [](int frames) {
    int n = 0, first = -1, last = -1;
    for (int k = 0; k < frames; ++k)
      if (app::html_frame_has_images(k, frames)) {
        ++n;
        if (first < 0) first = k;
        last = k;
      }
    return std::vector<int>{n, first, last};
  };
  CHECK(count(3) == std::vector<int>{3, 0, 2});
  CHECK(count(app::kHtmlMaxImageFrames) == std::vector<int>{64, 0, 63});
  CHECK(count(65)[0] == 64);
  CHECK(count(1000) == std::vector<int>{64, 0, 985});
  CHECK_FALSE(app::html_frame_has_images(3, 3));
  CHECK(app::html_images_note(64).empty());
  CHECK_THAT(app::html_images_note(1000), Catch::Contains("64 of the 1000 frames"));
}

TEST_CASE("report images: the previews' tonemap, downscaled to the limit; the error colour scale",
          "[app][html]") {
  Image flat(301, 300, 3, 0.25f);  // 90300 pixels: halved, the last column of boxes cut
  const io::Rgb8Image preview =
      io::decode_png_rgb8(app::preview_image("p", flat, 1.f).png, "preview");
  CHECK(preview.width == 151);
  CHECK(preview.height == 150);
  CHECK(
      io::decode_png_rgb8(app::preview_image("p", Image(1920, 1080, 3), 1.f).png, "1080p").width ==
      320);
  const uint8_t want = tonemap_channel(0.25f, 1.f);
  CHECK(std::count(preview.rgb.begin(), preview.rgb.end(), want) ==
        std::ptrdiff_t(preview.rgb.size()));
  Image small(6, 2, 3, 0.f);  // under the limit: kept as is
  small.at(5, 1, 0) = 1.f;
  const io::Rgb8Image kept = io::decode_png_rgb8(app::preview_image("s", small, 2.f).png, "kept");
  CHECK(kept.width == 6);
  CHECK(kept.rgb[(1 * 6 + 5) * 3] == tonemap_channel(1.f, 2.f));

  Image map(3, 1, 1);
  map.at(0, 0, 0) = 0.f;
  map.at(1, 0, 0) = 1.f;
  map.at(2, 0, 0) = NAN;  // as no error
  const io::Rgb8Image colours = io::decode_png_rgb8(app::error_map_image("e", map).png, "map");
  CHECK(std::vector<uint8_t>(colours.rgb.begin(), colours.rgb.begin() + 3) ==
        std::vector<uint8_t>{0, 0, 4});
  CHECK(std::vector<uint8_t>(colours.rgb.begin() + 3, colours.rgb.begin() + 6) ==
        std::vector<uint8_t>{252, 253, 191});
  CHECK(std::vector<uint8_t>(colours.rgb.begin() + 6, colours.rgb.end()) ==
        std::vector<uint8_t>{0, 0, 4});
  // FLIP of the previews: the map itself up to the limit; beyond, of the downscaled images for an
  // observer scaled alike, which for flat images is the full map's value.
  Image grey(301, 300, 3, 0.2f), light(301, 300, 3, 0.6f);
  const Image full = metrics::flip_map(grey, light), half = app::preview_flip_map(grey, light);
  CHECK(half.width() == 151);
  CHECK(half.at(70, 70, 0) == Approx(full.at(140, 140, 0)).epsilon(1e-5));
  const Image small_grey(6, 2, 3, 0.2f);
  CHECK(app::preview_flip_map(small, small_grey).data() ==
        metrics::flip_map(small, small_grey).data());

  const app::HtmlColourBar bar = app::error_map_colour_bar();
  CHECK(bar.colours.front() == "#000004");
  CHECK(bar.colours.back() == "#fcfdbf");
}

TEST_CASE("svgf denoise and svgf compare write report.html", "[app][html]") {
  const fs::path in = test::write_synthetic(test::scratch("html_in"), 3),
                 out = test::scratch("html_out"), plain = test::scratch("html_plain"),
                 work = test::scratch("html_work");
  fs::create_directories(work);
  REQUIRE(app::denoise_command(
              {in.string(), out.string(), "--backend", "cpu", "--method", "gaussian"}) == 0);
  const std::string page = test::file_bytes(out / app::kReportHtml);
  CHECK(test::tags(page, "div class=\"frame\"").size() == 3);
  // noisy, denoised, reference, FLIP error for each frame (the synthetic frames have references)
  const auto imgs = test::frame_images(page);
  REQUIRE(imgs.size() == 12);
  for (const std::string& img : imgs) {
    const io::Rgb8Image im = test::image_of_src(test::attribute(img, "src"));
    CHECK(im.width == test::SyntheticScene{}.width);
  }
  CHECK(test::attribute(imgs[3], "data-name") == "FLIP error");
  const auto plots = plots_of(page);
  REQUIRE(plots.size() == 3);  // PSNR, relMSE, time
  CHECK(plot_points(plots[0]) == 6);
  CHECK_THAT(page, Catch::Contains("gaussian cpu exact"));

  // --no-preview: no images in the page either.
  REQUIRE(app::denoise_command({in.string(), plain.string(), "--backend", "cpu", "--method",
                                "gaussian", "--no-preview"}) == 0);
  const std::string bare = test::file_bytes(plain / app::kReportHtml);
  CHECK(test::frame_images(bare).empty());
  CHECK_THAT(bare, Catch::Contains("--no-preview"));

  // compare: beside --json, or --html FILE; a sequence as B adds its noisy frames.
  REQUIRE(app::compare_command({out.string(), in.string(), "--json", (work / "c.json").string()}) ==
          0);
  const std::string cmp = test::file_bytes(work / "c.html");
  const auto cmp_imgs = test::frame_images(cmp);
  REQUIRE(cmp_imgs.size() == 12);
  CHECK(test::attribute(cmp_imgs[0], "data-name") == "noisy");
  CHECK(test::attribute(cmp_imgs[2], "data-name") == "reference");
  CHECK(plots_of(cmp).size() == 4);  // PSNR, SSIM, relMSE, FLIP
  REQUIRE(app::compare_command(
              {out.string(), plain.string(), "--html", (work / "d.html").string()}) == 0);
  const auto plain_imgs = test::frame_images(test::file_bytes(work / "d.html"));
  REQUIRE(plain_imgs.size() == 9);  // A, B, FLIP error
  CHECK(test::attribute(plain_imgs[1], "data-name") == "B");
  CHECK_FALSE(fs::exists(work / "d.json"));
  // A --json FILE ending in .html keeps its JSON: the page goes to FILE.html.
  const std::string e = (work / "e.html").string();
  REQUIRE(app::compare_command({out.string(), in.string(), "--json", e}) == 0);
  CHECK(test::read_json(work / "e.html")["frames"].size() == 3);
  CHECK(test::frame_images(test::file_bytes(work / "e.html.html")).size() == 12);
  CHECK_THROWS_AS(app::compare_command({out.string(), in.string(), "--json", (work / "f").string(),
                                        "--html", (work / "f").string()}),
                  app::UsageError);
  fs::remove_all(in);
  fs::remove_all(work);
  test::remove_output(out);
  test::remove_output(plain);
}
