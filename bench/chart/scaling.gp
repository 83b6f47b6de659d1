# Time against pixels (log-log) and against a-trous iterations. Called by bench/chart.sh with
# data = chart-data folder, out_pixels and out_iterations = PNG paths.
set terminal pngcairo size 1100,720 font "DejaVu Sans,11"
set grid xtics ytics mxtics mytics
set key left top box
s(name) = data . "/" . name . ".dat"
has(name) = system("grep -vsc '^#' " . s(name) . " || true") + 0 > 0

set output out_pixels
set title "Time per frame against pixels (filter stages, median)"
set xlabel "megapixels (log)"
set ylabel "ms per frame (log)"
set logscale xy
# Reference line through the largest CPU point: what time linear in pixels would be.
ref_x = 1; ref_y = 0
if (has("scaling_pixels_cpu_tmax")) { stats s("scaling_pixels_cpu_tmax") using 1:2 nooutput; ref_x = STATS_max_x; ref_y = STATS_max_y }
linear(x) = ref_y > 0 ? ref_y * x / ref_x : 1/0
plot \
  linear(x) with lines dt 2 lc rgb "#999999" title "linear in pixels (through the CPU, all threads, at the largest size)", \
  s("scaling_pixels_cpu_t1") using 1:2 with linespoints pt 7 lc rgb "#1f77b4" title "CPU 1 thread", \
  s("scaling_pixels_cpu_tmax") using 1:2 with linespoints pt 5 lc rgb "#17becf" title "CPU, all threads", \
  s("scaling_pixels_cuda_exact") using 1:2 with linespoints pt 9 lc rgb "#2ca02c" title "CUDA exact", \
  s("scaling_pixels_cuda_fast") using 1:2 with linespoints pt 11 lc rgb "#d62728" title "CUDA fast", \
  s("scaling_pixels_cpu_t1") using 1:2:4 with labels offset 0,1 font ",8" notitle

set output out_iterations
set title "Time per frame against a-trous iterations (median)"
set xlabel "a-trous iterations"
set ylabel "ms per frame (log)"
unset logscale x
set logscale y
set xtics 1
plot \
  s("scaling_iterations_cpu") using 1:2 with linespoints pt 7 lc rgb "#1f77b4" title "CPU exact, all threads", \
  s("scaling_iterations_cuda_exact") using 1:2 with linespoints pt 9 lc rgb "#2ca02c" title "CUDA exact", \
  s("scaling_iterations_cuda_fast") using 1:2 with linespoints pt 11 lc rgb "#d62728" title "CUDA fast"
