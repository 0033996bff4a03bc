set terminal pngcairo size 1000,640 font "DejaVu Sans,10" noenhanced
set datafile missing "?"
set output "table2.png"
set multiplot layout 1,2 title "Table 2 on this machine: cornell_box, 128x128, 16 passes x 50000 photons"
set grid
set logscale y
set key top left
set xlabel "frames F"
set xrange [0:*]
set ylabel "seconds"
set title "time to render F frames (solid: wall, dashed: CPU)"
plot "plots/table2.dat" using 1:2 with linespoints lw 2 pt 7 lc 1 title "ours (one convergence)", \
     "plots/table2.dat" using 1:3 with linespoints lw 2 pt 5 lc 2 title "frame by frame, measured", \
     "plots/table2.dat" using 1:4 with lines dt 3 lw 2 lc 3 title "frame by frame, F x fastest frame", \
     "plots/table2.dat" using 1:5 with linespoints dt 2 pt 6 lc 1 notitle, \
     "plots/table2.dat" using 1:6 with linespoints dt 2 pt 4 lc 2 notitle
set ylabel "CPU time / ours(1)"
set title "relative to one frame (CPU time), against the paper"
plot "plots/table2.dat" using 1:8 with linespoints lw 2 pt 7 lc 1 title "ours", \
     "plots/table2.dat" using 1:9 with linespoints lw 2 pt 5 lc 2 title "frame by frame", \
     "plots/table2.dat" using 1:10 with linespoints dt 2 pt 6 lc 1 title "paper: ours", \
     "plots/table2.dat" using 1:11 with linespoints dt 2 pt 4 lc 2 title "paper: frame by frame"
unset multiplot
