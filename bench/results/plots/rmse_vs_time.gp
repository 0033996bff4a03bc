set terminal pngcairo size 1000,640 font "DejaVu Sans,10" noenhanced
set datafile missing "?"
set key top right
set grid
set logscale xy
set output "rmse_vs_time.png"
set title "cornell_box, 128x128, 48 frames: RMSE against wall time (2 threads)"
set xlabel "wall time (s)"
set ylabel "RMSE against the reference (W sr^-1 m^-2)"
plot "plots/conv_single.dat" using 2:4 with linespoints lw 2 pt 7 title "single: steady", \
     "plots/conv_single.dat" using 2:6 with linespoints lw 2 pt 5 title "single: frames (mean)", \
     "plots/conv_fbf.dat" using 2:4 with linespoints lw 2 pt 6 title "frame by frame: steady", \
     "plots/conv_fbf.dat" using 2:6 with linespoints lw 2 pt 4 title "frame by frame: frames (mean)"
