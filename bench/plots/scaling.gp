# Viewport scaling: ms per frame against the number of views (scripts/results/run.py).
load "bench/plots/common.gp"
set logscale xy 2
set xlabel "views per frame (N)"
set ylabel "ms per frame"
set xtics (1, 2, 4, 8, 16, 32, 48)
plot datafile using "views":"frame_ms" with linespoints lw 2 title "frame (one probe update, N views)", \
     datafile using "views":"naive_ms" with linespoints dt 2 title "naive: a probe update per view", \
     datafile using "views":"raster_ms" with linespoints title "raster, all views", \
     datafile using "views":"probe_update_ms" with linespoints title "probe update", \
     datafile using "views":"trivial_floor_ms" with linespoints dt 3 title "trivial-shader floor (N views, constant colour)"
