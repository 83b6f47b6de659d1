# The CIS 565 kernel-size study: mean PSNR over the fixture scenes against time per frame for the
# wavelet filter at 3x3 to 9x9 and its 9x9 comparisons (a Gaussian, a dense edge-stopping JBF),
# on each platform. A dashed vertical line marks each platform's Gaussian time: a wavelet point
# left of it and above the Gaussian point is better at no more time. Called by bench/chart.sh
# with data = chart-data folder, out = PNG path, subtitle = where the times come from.
set terminal pngcairo size 1280,820 font "DejaVu Sans,11"
set output out
set title "CIS 565 kernel-size study: wavelet 3x3 to 9x9 against a 9x9 Gaussian\n{/*0.8 " . subtitle . "}"
set xlabel "time per frame, ms (median of the filter stages; log scale)"
set ylabel "mean PSNR over the fixture scenes, dB (higher is better)"
set logscale x
set grid xtics ytics mxtics
set key outside right top box
f(plat, filter) = data . "/kernel_study_" . plat . "_" . filter . ".dat"
has(file) = system("grep -vsc '^#' " . file . " || true") + 0 > 0
# The PSNR range over every file, for the equal-time lines.
ymin = 1e9; ymax = -1e9
do for [plat in "cpu cuda_exact cuda_fast"] {
  do for [filter in "wavelet gaussian dense"] {
    if (has(f(plat, filter))) {
      stats f(plat, filter) using 2 nooutput
      ymin = (STATS_min < ymin) ? STATS_min : ymin
      ymax = (STATS_max > ymax) ? STATS_max : ymax
    }
  }
}
if (ymin > ymax) { ymin = 0; ymax = 1 }
pad = (ymax - ymin) * 0.1 + 0.1
set yrange [ymin - pad : ymax + pad]
# Series without points (say, no GPU results yet) are skipped with a gnuplot warning.
plot \
  f("cpu", "wavelet") using 1:2 with linespoints lc rgb "#17becf" pt 7 ps 1.3 title "wavelet CPU exact", \
  f("cpu", "wavelet") using 1:2:4 with labels offset 0.6,0.7 left font ",8" tc rgb "#17becf" notitle, \
  f("cpu", "gaussian") using 1:2 with points lc rgb "#bcbd22" pt 5 ps 1.8 title "9x9 Gaussian CPU", \
  f("cpu", "gaussian") using 1:(ymin - pad):(0):(ymax - ymin + 2 * pad) with vectors nohead dt 2 lc rgb "#bcbd22" notitle, \
  f("cpu", "dense") using 1:2 with points lc rgb "#e7969c" pt 13 ps 1.8 title "9x9 dense JBF CPU", \
  f("cuda_exact", "wavelet") using 1:2 with linespoints lc rgb "#8c564b" pt 9 ps 1.3 title "wavelet CUDA exact", \
  f("cuda_exact", "wavelet") using 1:2:4 with labels offset 0.6,-0.7 left font ",8" tc rgb "#8c564b" notitle, \
  f("cuda_exact", "gaussian") using 1:2 with points lc rgb "#6b6ecf" pt 5 ps 1.8 title "9x9 Gaussian CUDA exact", \
  f("cuda_exact", "gaussian") using 1:(ymin - pad):(0):(ymax - ymin + 2 * pad) with vectors nohead dt 2 lc rgb "#6b6ecf" notitle, \
  f("cuda_exact", "dense") using 1:2 with points lc rgb "#393b79" pt 13 ps 1.8 title "9x9 dense JBF CUDA exact", \
  f("cuda_fast", "wavelet") using 1:2 with linespoints lc rgb "#e377c2" pt 11 ps 1.3 title "wavelet CUDA fast", \
  f("cuda_fast", "wavelet") using 1:2:4 with labels offset -0.6,0.7 right font ",8" tc rgb "#e377c2" notitle, \
  f("cuda_fast", "gaussian") using 1:2 with points lc rgb "#b5cf6b" pt 5 ps 1.8 title "9x9 Gaussian CUDA fast", \
  f("cuda_fast", "gaussian") using 1:(ymin - pad):(0):(ymax - ymin + 2 * pad) with vectors nohead dt 2 lc rgb "#b5cf6b" notitle, \
  f("cuda_fast", "dense") using 1:2 with points lc rgb "#843c39" pt 13 ps 1.8 title "9x9 dense JBF CUDA fast"
