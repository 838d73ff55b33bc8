# fig5_elcentro_loops.gp - drawn by 'seislide study'; run in this folder: gnuplot fig5_elcentro_loops.gp
set terminal svg size 900,560 font 'Helvetica,13' background '#ffffff'
set output 'fig5_elcentro_loops.svg'
set grid lc rgb '#dddddd'
set key box opaque
set datafile missing 'NaN'
set multiplot layout 1,2 title 'Hysteresis loops, El Centro #9 at 0.8 g, mu = 0.1 (study Fig. 3-9)'
set xlabel 'u_x (mm)'
set ylabel 'F_x / W'
plot 'p2_x.tsv' u ($2*1e3):4 w l lw 1 t 'x alone', 'p2_xy.tsv' u ($2*1e3):4 w l lw 1 t 'x+y'
set xlabel 'u_y (mm)'
set ylabel 'F_y / W'
plot 'p2_y.tsv' u ($2*1e3):4 w l lw 1 t 'y alone', 'p2_xy.tsv' u ($3*1e3):5 w l lw 1 t 'x+y'
unset multiplot
