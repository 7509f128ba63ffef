# Probe scheduling: error against the rays spent, uniform and visibility schedules. Top: RMSE
# against the path-traced reference; bottom: against the renderer's converged image.
load "bench/plots/common.gp"
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { set terminal pngcairo size 900,800 enhanced font "sans,10" } else { set terminal png size 900,800 }
set output outfile
set multiplot layout 2,1 title plottitle noenhanced
unset title
set logscale x 10
set xlabel "probe rays spent (cumulative)"
set ylabel "RMSE against the reference"
plot datafile using (strcol("mode") eq "uniform" ? column("rays") : NaN):"rmse" with linespoints title "uniform (every probe)", \
     datafile using (strcol("mode") eq "visibility" ? column("rays") : NaN):"rmse" with linespoints title "visibility schedule"
set ylabel "RMSE against the converged image"
plot datafile using (strcol("mode") eq "uniform" ? column("rays") : NaN):"rmse_vs_converged" with linespoints title "uniform (every probe)", \
     datafile using (strcol("mode") eq "visibility" ? column("rays") : NaN):"rmse_vs_converged" with linespoints title "visibility schedule"
unset multiplot
