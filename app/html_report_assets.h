#pragma once
// The inline style and script of report.html (app/html_report.cpp writes the rest).

namespace svgf::app {

inline constexpr const char* kStyle = R"(
body { font: 14px/1.4 system-ui, sans-serif; margin: 16px; color: #222; background: #fff; }
h1 { font-size: 20px; margin: 0 0 4px; }
h2 { font-size: 16px; margin: 18px 0 6px; }
.sub, .note { color: #555; margin: 0 0 8px; }
.controls { display: flex; align-items: center; gap: 8px; margin: 8px 0; }
.controls input[type=range] { width: 320px; }
#frame-label { font-weight: 600; }
.frame { display: flex; flex-wrap: wrap; gap: 8px; }
.frame[hidden] { display: none; }
.frame figure, .plot-box { margin: 0; }
.frame img { display: block; image-rendering: pixelated; }
figcaption { font-size: 12px; color: #444; }
.colour-bar { display: flex; align-items: center; gap: 6px; font-size: 12px; margin: 6px 0; }
.colour-bar .bar { display: inline-block; width: 200px; height: 10px; }
.row { display: flex; flex-wrap: wrap; gap: 24px; align-items: flex-start; margin-top: 12px; }
.wipe-box { position: relative; width: 512px; max-width: 100%; }
.wipe-box img { display: block; width: 100%; height: auto; image-rendering: pixelated; }
.wipe-box img#wipe-a { position: absolute; left: 0; top: 0; }
#wipe { width: 512px; max-width: 100%; }
.plots { display: flex; flex-wrap: wrap; gap: 16px; }
svg.plot { display: block; font-size: 10px; cursor: crosshair; }
svg.plot .area { fill: #fafafa; stroke: #999; }
svg.plot .grid { stroke: #ddd; }
svg.plot .tick { fill: #555; }
svg.plot .cursor { stroke: #000; stroke-dasharray: 3 3; }
svg.plot polyline { stroke-width: 1.5; }
.key { margin-left: 8px; white-space: nowrap; }
.swatch { display: inline-block; width: 12px; height: 3px; vertical-align: middle;
          margin-right: 3px; }
table { border-collapse: collapse; margin: 0 24px 12px 0; display: inline-table;
        vertical-align: top; }
caption { text-align: left; font-weight: 600; padding-bottom: 4px; }
th, td { text-align: left; padding: 2px 10px 2px 0; border-bottom: 1px solid #eee;
         font-weight: normal; }
th { color: #555; }
td { font-variant-numeric: tabular-nums; }
)";

// The frame selector (slider, buttons, arrow keys, a click on a plot), the wipe between two of
// the frame's images, the selected frame's numbers. Once every image has decoded it marks the
// body data-ready="1" with what it found (decoded images, points per plot, element positions),
// which tests read through a headless browser (tests/app_html_report_test.cpp).
inline constexpr const char* kScript = R"(
(function () {
  'use strict';
  const data = JSON.parse(document.getElementById('report-data').textContent);
  const n = data.frames.length;
  const slider = document.getElementById('frame');
  const frames = Array.from(document.querySelectorAll('.frame'));
  const plots = Array.from(document.querySelectorAll('svg.plot'));
  const pickA = document.getElementById('wipe-left'), pickB = document.getElementById('wipe-right');
  const wipe = document.getElementById('wipe');
  let current = 0;
  function fmt(v) { return v === null ? '\u2013' : Number(v.toPrecision(5)).toString(); }
  function source(k, name) {
    const img = frames[k] && frames[k].querySelector('img[data-name="' + CSS.escape(name) + '"]');
    return img ? img.src : '';
  }
  function showWipe() {
    const a = source(current, pickA.value), b = source(current, pickB.value);
    document.getElementById('wipe-panel').hidden = !(a && b);
    if (a && b) {
      document.getElementById('wipe-a').src = a;
      document.getElementById('wipe-b').src = b;
    }
    document.getElementById('wipe-a').style.clipPath = 'inset(0 ' + (100 - wipe.value) + '% 0 0)';
  }
  function show(k) {
    current = Math.max(0, Math.min(n - 1, k));
    slider.value = current;
    document.getElementById('frame-label').textContent =
        (current + 1) + ' / ' + n + ': ' + data.frames[current];
    frames.forEach(function (f, i) { f.hidden = i !== current; });
    plots.forEach(function (svg) {
      const x0 = Number(svg.dataset.x0), x1 = Number(svg.dataset.x1);
      const x = n > 1 ? x0 + (x1 - x0) * current / (n - 1) : x0;
      const c = svg.querySelector('.cursor');
      c.setAttribute('x1', x);
      c.setAttribute('x2', x);
    });
    const rows = [];
    data.plots.forEach(function (p) {
      p.series.forEach(function (s) {
        rows.push('<tr><th>' + p.title.replace(/</g, '&lt;') + ', ' + s.name.replace(/</g, '&lt;') +
                  '</th><td>' + fmt(s.values[current]) + '</td></tr>');
      });
    });
    document.getElementById('frame-values').innerHTML = rows.join('');
    showWipe();
    document.body.dataset.frame = current;
  }
  slider.addEventListener('input', function () { show(Number(slider.value)); });
  document.getElementById('prev').addEventListener('click', function () { show(current - 1); });
  document.getElementById('next').addEventListener('click', function () { show(current + 1); });
  document.addEventListener('keydown', function (e) {
    if (e.target.tagName === 'SELECT' || e.target.tagName === 'INPUT') return;
    if (e.key === 'ArrowLeft') show(current - 1);
    if (e.key === 'ArrowRight') show(current + 1);
  });
  plots.forEach(function (svg) {
    svg.addEventListener('click', function (e) {
      const r = svg.getBoundingClientRect();
      const x = (e.clientX - r.left) * svg.viewBox.baseVal.width / r.width;
      const x0 = Number(svg.dataset.x0), x1 = Number(svg.dataset.x1);
      show(n > 1 ? Math.round((x - x0) / (x1 - x0) * (n - 1)) : 0);
    });
  });
  [pickA, pickB, wipe].forEach(function (el) { el.addEventListener('input', showWipe); });
  const start = /^#frame=(\d+)$/.exec(location.hash);  // report.html#frame=K: the K-th frame
  show(start ? Number(start[1]) : 0);

  function rect(el) {
    const r = el.getBoundingClientRect();
    return [r.left + window.scrollX, r.top + window.scrollY, r.width, r.height]
        .map(Math.round).join(',');
  }
  // After the window's load event every image has loaded (or failed): the marks are set in
  // that event's handler, so a tool that reads the page once it has loaded (a headless
  // browser's --dump-dom) finds them whatever the machine's load (img.decode()'s promises
  // settled after the dump on a busy 2-core machine).
  const images = Array.from(document.querySelectorAll('.frame img'));
  function mark() {
    const decoded = images.map(function (img) { return img.complete && img.naturalWidth > 0; });
    const ok = decoded.filter(Boolean).length;
    images.forEach(function (img) {
      if (!img.closest('.frame').hidden) img.dataset.rect = rect(img);
    });
    plots.forEach(function (svg) {
      let points = svg.querySelectorAll('circle.point').length;
      svg.querySelectorAll('polyline').forEach(function (l) { points += l.points.numberOfItems; });
      svg.dataset.parsedPoints = points;
      svg.dataset.rect = rect(svg);
    });
    document.body.dataset.imagesDecoded = ok;
    document.body.dataset.imagesFailed = decoded.length - ok;
    document.body.dataset.ready = '1';
  }
  if (document.readyState === 'complete') mark();
  else window.addEventListener('load', mark);
})();
)";

}  // namespace svgf::app
