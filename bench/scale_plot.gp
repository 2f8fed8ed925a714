# The scale bench's plot (bench/README.md, "Scale"): CPU seconds and peak memory against the input's vertices,
# log-log, from the rows of bench/scale_table.sh.
#   gnuplot -e "rows='scale_rows.tsv'; out='bench/scale.png'" bench/scale_plot.gp
if (!exists("rows")) rows = 'scale_rows.tsv'
if (!exists("out")) out = 'scale.png'
set terminal pngcairo size 1200,500 font ",11"
set output out
set datafile separator "\t"
set logscale xy
set grid
set key top left
set xlabel "input vertices"
set format x "10^{%T}"
set xrange [1e5:2e7]
# The rows of one tool that succeeded (exit 0), by input size.
of(tool) = sprintf("< awk -F'\t' '$3 == \"%s\" && $6 == 0' '%s' | sort -t '\t' -k2,2n", tool, rows)
set multiplot layout 1,2 title "prm pack --target-error 2e-4, prm remesh --grid (fixed), draco\\_encoder -qp 11 -cl 10 (igea, midpoint-subdivided)"
set ylabel "CPU seconds (user + system)"
plot of("pack") using 2:4 with linespoints lw 2 pt 7 title "prm pack", \
     of("remesh") using 2:4 with linespoints lw 2 pt 5 title "prm remesh (fixed grid)", \
     of("draco") using 2:4 with linespoints lw 2 pt 9 title "draco\\_encoder"
set ylabel "peak resident memory (MB)"
plot of("pack") using 2:($5 / 1024) with linespoints lw 2 pt 7 title "prm pack", \
     of("remesh") using 2:($5 / 1024) with linespoints lw 2 pt 5 title "prm remesh (fixed grid)", \
     of("draco") using 2:($5 / 1024) with linespoints lw 2 pt 9 title "draco\\_encoder", \
     [1e5:2e7] x * 0.6 / 1024 with lines dt 2 lc rgb "gray" title "0.6 KB per input vertex"
unset multiplot
