# Old against new densifier (bench/compare_densify.sh, bench/RESULTS.md "Densifying packer: overlap
# transfer"): solid fraction against CPU time and against sweeps, from PREFIX-old.curve and
# PREFIX-new.curve ("cpu_seconds sweeps solid_fraction").
# Run from the repository root:
#   gnuplot -e "prefix='/tmp/cmp10k'; label='single size, 9,078 particles'" bench/densify_compare_plot.gp
# Optional: out (PNG path), old_title / new_title (the two curves' names), what (the title's
# "A against B").
set terminal pngcairo size 1100,440 font "sans,10"
if (!exists("prefix")) prefix = "cmp10k"
if (!exists("label")) label = "single size"
if (!exists("out")) out = "docs/images/densify-old-vs-new.png"
if (!exists("old_title")) old_title = "earlier (no transfer)"
if (!exists("new_title")) new_title = "overlap transfer"
if (!exists("what")) what = "earlier schedule against overlap transfer"
set output out
set multiplot layout 1,2 title "aggpack densify, ".label.": ".what." (paired runs, one thread each, shared machine)"
set key bottom right
set grid
set ylabel "solid fraction (last overlap-free checkpoint)"
set xlabel "CPU time (s)  (idle 2 cores at -j 0: wall about CPU / 2)"
plot prefix."-old.curve" using 1:3 with lines lw 2 title old_title, \
     prefix."-new.curve" using 1:3 with lines lw 2 title new_title, \
     0.60 with lines dt 2 lc rgb "gray" title "0.60"
set xlabel "sweeps"
set ylabel ""
plot prefix."-old.curve" using 2:3 with lines lw 2 notitle, \
     prefix."-new.curve" using 2:3 with lines lw 2 notitle, \
     0.60 with lines dt 2 lc rgb "gray" notitle
unset multiplot
