# Per-frame error curves of one fixture scene: PSNR, FLIP and the frame-to-frame error change.
# Called by bench/chart.sh with data = chart-data folder, scene = scene name, out = PNG path,
# quality_on = the scenes' source ("the fixture scenes", "the evaluation set (...)").
set terminal pngcairo size 1280,1000 font "DejaVu Sans,10"
set output out
set multiplot layout 3,1 title "Per-frame error, " . scene . ", from " . quality_on
set grid
set key outside right top
set xlabel "frame"
set style data linespoints
metrics = "psnr flip error_change"
names = "'PSNR, dB (higher is better)' 'FLIP (lower is better)' 'error change |e_t - e_{t-1}| (lower is better)'"
do for [m = 1:3] {
  file = data . "/errors_" . scene . "_" . word(metrics, m) . ".dat"
  stats file skip 1 nooutput
  n = STATS_columns
  set ylabel word(names, m)
  if (m == 3) { set logscale y } else { unset logscale y }
  plot for [c = 2:n] file using 1:c title columnheader(c) noenhanced pt (c + 3) ps 0.8
}
unset multiplot
