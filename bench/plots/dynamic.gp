# Dynamic light (scripts/results/dynamic.py): one panel per event of scenes/cornell_light.gltf
# (the light jumps, is switched off, on again), one line per run (hysteresis/blend): per frame
# after the event, the RMSE against an independent converged run of the new state (the lag; log
# scale, where a running average's decay is a straight line of slope log(alpha)).
# Extra variables: slist='h0.9/per-update h0.95/per-update ...' (the "series" column's values),
# elist='jump off on' (the "event" column's values).
load "bench/plots/common.gp"
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { set terminal pngcairo size 900,1000 enhanced font "sans,10" } else { set terminal png size 900,1000 }
set output outfile
set multiplot layout words(elist),1 title plottitle noenhanced
set logscale y
set xlabel "frames after the event"
set ylabel "lag RMSE (vs converged run)"
do for [e in elist] {
  set title "event: ".e noenhanced
  plot for [s in slist] datafile using \
       ((strcol("series") eq s && strcol("event") eq e) ? column("frames_after_event") : NaN):"lag_rmse" \
       with lines lw 2 title s noenhanced
}
unset multiplot
