# Shared settings of the results plots (loaded by the others). The caller passes
#   -e "datafile='X.csv'; outfile='X.png'; plottitle='...'"
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
  set terminal pngcairo size 900,600 enhanced font "sans,10"
} else {
  set terminal png size 900,600
}
set output outfile
set datafile separator ","
set datafile columnheaders
set datafile missing ""
set grid
set key outside right top
set title plottitle noenhanced
