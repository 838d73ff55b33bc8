# fig3_elcentro_ux.gp - drawn by 'seislide study'; run in this folder: gnuplot fig3_elcentro_ux.gp
set terminal svg size 900,560 font 'Helvetica,13' background '#ffffff'
set output 'fig3_elcentro_ux.svg'
set grid lc rgb '#dddddd'
set key box opaque
set datafile missing 'NaN'
set title 'El Centro #9, RG 1.60 at 0.8 g, mu = 0.1: u_x (study Fig. 3-7)'
set xlabel 'time (s)'
set ylabel 'u_x (mm)'
plot 'p2_x.tsv' u 1:($2*1e3) w l lw 2 t 'x', 'p2_xy.tsv' u 1:($2*1e3) w l lw 2 t 'x+y', \
  'p2_xz.tsv' u 1:($2*1e3) w l lw 2 dt 2 t 'x+z', 'p2_xyz.tsv' u 1:($2*1e3) w l lw 2 dt 3 t 'x+y+z'
