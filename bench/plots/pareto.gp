# Error against run time: PSNR against ms per frame, probe settings and baselines.
# Extra variable: frontfile='pareto_front_SCENE.csv' (the non-dominated rows, sorted by time).
load "bench/plots/common.gp"
set logscale x 10
set xlabel "ms per frame"
set ylabel "PSNR (dB) against the reference"
is(m) = strcol("method") eq m
plot frontfile using "ms_per_frame":"psnr" with lines lw 2 lc rgb "gray50" title "Pareto front", \
     datafile using (is("probes") ? column("ms_per_frame") : NaN):"psnr" with points pt 7 ps 1.2 title "probes (sweeps)", \
     datafile using (is("probes") ? column("ms_per_frame") : NaN):"psnr":(strcol("config")) with labels offset 0.6,0.6 left font ",7" noenhanced notitle, \
     datafile using (is("path tracing") ? column("ms_per_frame") : NaN):"psnr" smooth unique with linespoints pt 5 title "path tracing (k spp, equal time)", \
     datafile using (is("direct only") ? column("ms_per_frame") : NaN):"psnr" with points pt 9 ps 1.5 title "direct light only"
