# Fraction-vs-time plot of the densify runs in bench/RESULTS.md ("Densifying packer"): the
# F-*.trace files are `aggpack densify ... --trace F-<run>.trace` outputs. Run from the repository root: gnuplot -e "dir='TRACES'" bench/densify_plot.gp
set terminal pngcairo size 1100,480 font "sans,10"
if (!exists("dir")) dir = "."
set output "docs/images/densify-fraction-vs-time.png"
set multiplot layout 1,2 title "aggpack densify (HPMC, exact): solid fraction; shared 2-core machine under load (runs got 17-35 % of it)"
set key bottom right
set grid
set yrange [0.25:0.65]
set ylabel "solid fraction (bed: running estimate V / (A 2 z_{mean}))"
set xlabel "wall time (s)"
plot dir."/F-s1k.trace" using 1:3 with lines lw 2 title "single size, 856", \
     dir."/F-s10k.trace" using 1:3 with lines lw 2 title "single size, 9,078", \
     dir."/F-ful.trace" using 1:3 with lines lw 2 title "Fuller 4:1 q=0.5, 6,238", \
     dir."/F-bed.trace" using 1:3 with lines lw 2 title "bed, paper's particles, 1,014", \
     0.60 with lines dt 2 lc rgb "gray" title "target 0.60 (single size)"
set xlabel "sweeps"
set ylabel ""
set logscale x
plot dir."/F-s1k.trace" using ($2+1):3 with lines lw 2 notitle, \
     dir."/F-s10k.trace" using ($2+1):3 with lines lw 2 notitle, \
     dir."/F-ful.trace" using ($2+1):3 with lines lw 2 notitle, \
     dir."/F-bed.trace" using ($2+1):3 with lines lw 2 notitle, \
     0.60 with lines dt 2 lc rgb "gray" notitle
unset multiplot
