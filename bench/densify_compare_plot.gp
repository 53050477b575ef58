# Old against new densifier (bench/compare_densify.sh, bench/RESULTS.md "Densifying packer: overlap
# transfer"): solid fraction against CPU time and against sweeps, from PREFIX-old.curve and
# PREFIX-new.curve ("cpu_seconds sweeps solid_fraction").
# Run from the repository root:
#   gnuplot -e "prefix='/tmp/cmp10k'; label='single size, 9,078 particles'" bench/densify_compare_plot.gp
set terminal pngcairo size 1100,440 font "sans,10"
if (!exists("prefix")) prefix = "cmp10k"
if (!exists("label")) label = "single size"
if (!exists("out")) out = "docs/images/densify-old-vs-new.png"
set output out
set multiplot layout 1,2 title "aggpack densify, ".label.": earlier schedule against overlap transfer (paired runs, one thread each, shared machine)"
set key bottom right
set grid
set ylabel "solid fraction (last overlap-free checkpoint)"
set xlabel "CPU time (s)  (idle 2 cores at -j 0: wall about CPU / 2)"
plot prefix."-old.curve" using 1:3 with lines lw 2 title "earlier (no transfer)", \
     prefix."-new.curve" using 1:3 with lines lw 2 title "overlap transfer", \
     0.60 with lines dt 2 lc rgb "gray" title "0.60"
set xlabel "sweeps"
set ylabel ""
plot prefix."-old.curve" using 2:3 with lines lw 2 notitle, \
     prefix."-new.curve" using 2:3 with lines lw 2 notitle, \
     0.60 with lines dt 2 lc rgb "gray" notitle
unset multiplot
