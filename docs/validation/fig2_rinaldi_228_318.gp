# fig2_rinaldi_228_318.gp - drawn by 'seislide study'; run in this folder: gnuplot fig2_rinaldi_228_318.gp
set terminal svg size 900,560 font 'Helvetica,13' background '#ffffff'
set output 'fig2_rinaldi_228_318.svg'
set grid lc rgb '#dddddd'
set key box opaque
set datafile missing 'NaN'
set multiplot layout 2,1 title 'Rinaldi 228 + 318, mu = 0.3 (study Fig. 3-5)'
set xlabel 'time (s)'
set ylabel 'u_x (mm)'
plot [0:12] 'p1_2d_engine.tsv' u 1:($2*1e3) w l lw 3 lc rgb '#1f77b4' t 'engine', \
  'p1_2d_smooth.tsv' u 1:($2*1e3) w l lw 2 dt 2 lc rgb '#d62728' t 'smoothed', \
  'p1_2d_plastic.tsv' u 1:($2*1e3) w l lw 2 dt 3 lc rgb '#2ca02c' t 'elastic-plastic'
set ylabel 'u_y (mm)'
plot [0:12] 'p1_2d_engine.tsv' u 1:($3*1e3) w l lw 3 lc rgb '#1f77b4' t 'engine', \
  'p1_2d_smooth.tsv' u 1:($3*1e3) w l lw 2 dt 2 lc rgb '#d62728' t 'smoothed', \
  'p1_2d_plastic.tsv' u 1:($3*1e3) w l lw 2 dt 3 lc rgb '#2ca02c' t 'elastic-plastic'
unset multiplot
