# Fraction-vs-time plot of bench/run_densify.sh (bench/RESULTS.md, "Densifying packer"): the
# *.trace files are `aggpack densify ... --trace` outputs (seconds, sweeps, solid fraction).
# Run from the repository root: gnuplot -e "dir='bench-densify'" bench/densify_plot.gp
set terminal pngcairo size 1100,480 font "sans,10"
if (!exists("dir")) dir = "bench-densify"
set output "docs/images/densify-fraction-vs-time.png"
set multiplot layout 1,2 title "aggpack densify (HPMC, exact overlap test), idle 2-core VM: solid fraction against time and sweeps (bench/run_densify.sh)"
set key bottom right
set grid
set yrange [0.25:0.72]
set ylabel "solid fraction (bed: running estimate V / (A 2 z_{mean}))"
set xlabel "wall time (s)"
set logscale x
set xrange [1:1000]
plot dir."/single-10k-300s.trace" using 1:3 with lines lw 2 title "single size, 9,078", \
     dir."/single-100k-900s.trace" using 1:3 with lines lw 2 title "single size, 101,303", \
     dir."/fuller-10k-300s.trace" using 1:3 with lines lw 2 title "Fuller 5-20 mm q=0.5, 10,736", \
     dir."/bed-paper-60s.trace" using 1:3 with lines lw 2 title "bed, paper's particles, 1,014", \
     0.60 with lines dt 2 lc rgb "gray" title "targets 0.60 (single), 0.70 (Fuller)", \
     0.70 with lines dt 2 lc rgb "gray" notitle
set xlabel "sweeps"
set ylabel ""
set xrange [1:*]
plot dir."/single-10k-300s.trace" using ($2+1):3 with lines lw 2 notitle, \
     dir."/single-100k-900s.trace" using ($2+1):3 with lines lw 2 notitle, \
     dir."/fuller-10k-300s.trace" using ($2+1):3 with lines lw 2 notitle, \
     dir."/bed-paper-60s.trace" using ($2+1):3 with lines lw 2 notitle, \
     0.60 with lines dt 2 lc rgb "gray" notitle, 0.70 with lines dt 2 lc rgb "gray" notitle
unset multiplot
