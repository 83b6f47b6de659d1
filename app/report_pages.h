#pragma once
// The report.html pages of svgf denoise and svgf compare, from the JSON each writes.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/html_report.h"

namespace svgf::app {

// `report`: report.json's object, means included; `images`: per frame (in the report's order),
// empty where a frame has none; `images_note`: the page's sentence about which frames have them.
HtmlReport denoise_page(const nlohmann::json& report, std::vector<std::vector<HtmlImage>> images,
                        const std::string& images_note);

// `report`: the object of svgf compare's --json (a, b, frames, mean); the rest as above.
HtmlReport compare_page(const nlohmann::json& report, std::vector<std::vector<HtmlImage>> images,
                        const std::string& images_note);

}  // namespace svgf::app
