# Quality against time per frame, Pareto front marked. Called by bench/chart.sh with
#   data = folder of svgf-bench chart-data's tables, out = PNG path,
#   metric = "psnr" (column 2, higher is better) or "flip" (column 3, lower is better),
#   subtitle = where the times come from, quality_on = where the quality was measured.
set terminal pngcairo size 1280,820 font "DejaVu Sans,11"
set output out
col = (metric eq "psnr") ? 2 : 3
set title (metric eq "psnr" ? "Mean PSNR" : "Mean FLIP") . " over " . quality_on . " against time per frame\n{/*0.8 " . subtitle . "}"
set xlabel "time per frame, ms (median of the filter stages; log scale)"
set ylabel (metric eq "psnr" ? "PSNR, dB (higher is better)" : "FLIP (lower is better)")
set logscale x
set grid xtics ytics mxtics
set key outside right top box
set style line 1 lc rgb "#1f77b4" pt 7 ps 1.4
set style line 2 lc rgb "#2ca02c" pt 5 ps 1.4
set style line 3 lc rgb "#d62728" pt 9 ps 1.6
set style line 4 lc rgb "#7f7f7f" pt 13 ps 1.5
set style line 5 lc rgb "#17becf" pt 11 ps 1.4
set style line 6 lc rgb "#8c564b" pt 3 ps 1.4
set style line 7 lc rgb "#e377c2" pt 15 ps 1.4
set style line 8 lc rgb "#9467bd" lw 2 dt 2
set style line 9 lc rgb "#ff7f0e" lw 2 dt 2
set style line 10 lc rgb "#bcbd22" pt 4 ps 1.3
set style line 11 lc rgb "#6b6ecf" pt 6 ps 1.3
set style line 12 lc rgb "#b5cf6b" pt 8 ps 1.3
set style line 13 lc rgb "#e7969c" pt 12 ps 1.5
set style line 14 lc rgb "#393b79" pt 10 ps 1.5
set style line 15 lc rgb "#843c39" pt 14 ps 1.5
set style line 16 lc rgb "#000000" pt 5 ps 1.6
set style line 17 lc rgb "#636363" pt 7 ps 1.6
set style line 18 lc rgb "#a55194" pt 9 ps 1.8
front(plat) = data . "/pareto_" . metric . "_" . plat . ".dat"
f(s) = data . "/points_" . s . ".dat"
# Series without points (say, no GPU results yet) are skipped with a gnuplot warning.
plot \
  front("gpu") using 1:2 with steps ls 9 title "Pareto front, GPU", \
  front("gpu") using 1:2 with points pt 6 ps 2.6 lc rgb "#ff7f0e" notitle, \
  front("cpu") using 1:2 with steps ls 8 title "Pareto front, CPU", \
  front("cpu") using 1:2 with points pt 6 ps 2.6 lc rgb "#9467bd" notitle, \
  f("cpu_exact") using 1:col ls 1 title "SVGF CPU exact", \
  f("cpu_exact") using 1:col:6 with labels offset 0.6,0.7 left font ",8" tc rgb "#1f77b4" notitle, \
  f("cuda_exact") using 1:col ls 2 title "SVGF CUDA exact", \
  f("cuda_exact") using 1:col:6 with labels offset 0.6,-0.7 left font ",8" tc rgb "#2ca02c" notitle, \
  f("cuda_fast") using 1:col ls 3 title "SVGF CUDA fast", \
  f("cuda_fast") using 1:col:6 with labels offset -0.6,0.7 right font ",8" tc rgb "#d62728" notitle, \
  f("baselines") using 1:col ls 4 title "OpenCV baselines (CPU)", \
  f("baselines") using 1:col:6 with labels offset 0.6,0 left font ",8" tc rgb "#555555" notitle, \
  f("cpu_wavelet") using 1:col ls 5 title "wavelet CPU exact", \
  f("cpu_wavelet") using 1:col:6 with labels offset 0.6,0.7 left font ",8" tc rgb "#17becf" notitle, \
  f("cuda_exact_wavelet") using 1:col ls 6 title "wavelet CUDA exact", \
  f("cuda_exact_wavelet") using 1:col:6 with labels offset 0.6,-0.7 left font ",8" tc rgb "#8c564b" notitle, \
  f("cuda_fast_wavelet") using 1:col ls 7 title "wavelet CUDA fast", \
  f("cuda_fast_wavelet") using 1:col:6 with labels offset -0.6,0.7 right font ",8" tc rgb "#e377c2" notitle, \
  f("cpu_gaussian") using 1:col ls 10 title "Gaussian CPU exact", \
  f("cpu_gaussian") using 1:col:6 with labels offset 0.6,0.7 left font ",8" tc rgb "#bcbd22" notitle, \
  f("cuda_exact_gaussian") using 1:col ls 11 title "Gaussian CUDA exact", \
  f("cuda_exact_gaussian") using 1:col:6 with labels offset 0.6,-0.7 left font ",8" tc rgb "#6b6ecf" notitle, \
  f("cuda_fast_gaussian") using 1:col ls 12 title "Gaussian CUDA fast", \
  f("cuda_fast_gaussian") using 1:col:6 with labels offset -0.6,0.7 right font ",8" tc rgb "#b5cf6b" notitle, \
  f("cpu_jbf") using 1:col ls 13 title "JBF CPU exact", \
  f("cpu_jbf") using 1:col:6 with labels offset 0.6,0.7 left font ",8" tc rgb "#e7969c" notitle, \
  f("cuda_exact_jbf") using 1:col ls 14 title "JBF CUDA exact", \
  f("cuda_exact_jbf") using 1:col:6 with labels offset 0.6,-0.7 left font ",8" tc rgb "#393b79" notitle, \
  f("cuda_fast_jbf") using 1:col ls 15 title "JBF CUDA fast", \
  f("cuda_fast_jbf") using 1:col:6 with labels offset -0.6,0.7 right font ",8" tc rgb "#843c39" notitle, \
  f("cpu_bmfr") using 1:col ls 16 title "BMFR CPU exact", \
  f("cpu_bmfr") using 1:col:6 with labels offset 0.6,0.7 left font ",8" tc rgb "#000000" notitle, \
  f("cuda_exact_bmfr") using 1:col ls 17 title "BMFR CUDA exact", \
  f("cuda_exact_bmfr") using 1:col:6 with labels offset 0.6,-0.7 left font ",8" tc rgb "#636363" notitle, \
  f("cuda_fast_bmfr") using 1:col ls 18 title "BMFR CUDA fast", \
  f("cuda_fast_bmfr") using 1:col:6 with labels offset -0.6,0.7 right font ",8" tc rgb "#a55194" notitle
