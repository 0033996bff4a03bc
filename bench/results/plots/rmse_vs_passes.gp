set terminal pngcairo size 1000,640 font "DejaVu Sans,10" noenhanced
set datafile missing "?"
set key top right
set grid
set logscale xy
set output "rmse_vs_passes.png"
set title "cornell_box, 128x128, 48 frames, 50000 photons/pass: RMSE against passes (slopes: steady -0.453, photon-gathered part -0.344)"
set xlabel "passes"
set ylabel "RMSE against the reference (W sr^-1 m^-2)"
guide(x) = 0.179781 * (x / 2.0) ** (-1.0/3)
plot "plots/conv_single.dat" using 1:4 with linespoints lw 2 pt 7 title "single: steady", \
     "plots/conv_single.dat" using 1:6 with linespoints lw 2 pt 5 title "single: frames (mean)", \
     "plots/conv_fbf.dat" using 1:4 with points pt 6 ps 2 title "frame by frame: steady", \
     "plots/conv_fbf.dat" using 1:6 with points pt 4 ps 2 title "frame by frame: frames (mean)", \
     "plots/conv_single.dat" using 1:3 with lines dt 2 lc rgb "gray" title "single: steady, raw (reference noise in)", \
     "plots/conv_single.dat" using 1:7 with linespoints lw 2 pt 9 title "single: photon-gathered part of steady", \
     guide(x) with lines dt 3 lc rgb "black" title "passes^(-1/3)"
