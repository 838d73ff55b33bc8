# fig4_elcentro_uy.gp - drawn by 'seislide study'; run in this folder: gnuplot fig4_elcentro_uy.gp
set terminal svg size 900,560 font 'Helvetica,13' background '#ffffff'
set output 'fig4_elcentro_uy.svg'
set grid lc rgb '#dddddd'
set key box opaque
set datafile missing 'NaN'
set title 'El Centro #9, RG 1.60 at 0.8 g, mu = 0.1: u_y (study Fig. 3-8)'
set xlabel 'time (s)'
set ylabel 'u_y (mm)'
plot 'p2_y.tsv' u 1:($2*1e3) w l lw 2 t 'y', 'p2_xy.tsv' u 1:($3*1e3) w l lw 2 t 'x+y', \
  'p2_yz.tsv' u 1:($2*1e3) w l lw 2 dt 2 t 'y+z', 'p2_xyz.tsv' u 1:($3*1e3) w l lw 2 dt 3 t 'x+y+z'
