# Dynamic light: per frame after the block stops, one line per run (hysteresis/blend): the RMSE
# against the rest-pose reference (top) and against an independent rest-pose run (bottom: the lag).
# Extra variable: slist='h0.9/per-update h0.95/per-update ...' (the "series" column's values).
load "bench/plots/common.gp"
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { set terminal pngcairo size 900,800 enhanced font "sans,10" } else { set terminal png size 900,800 }
set output outfile
set multiplot layout 2,1 title plottitle noenhanced
unset title
set xlabel "frames after the block stops"
set ylabel "RMSE against the reference"
plot for [s in slist] datafile using (strcol("series") eq s ? column("frames_after_stop") : NaN):"rmse" \
     with lines lw 2 title s noenhanced
set ylabel "RMSE against an independent rest-pose run"
plot for [s in slist] datafile using (strcol("series") eq s ? column("frames_after_stop") : NaN):"rmse_vs_end" \
     with lines lw 2 title s noenhanced
unset multiplot
