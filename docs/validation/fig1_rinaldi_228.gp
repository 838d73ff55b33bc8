# fig1_rinaldi_228.gp - drawn by 'seislide study'; run in this folder: gnuplot fig1_rinaldi_228.gp
set terminal svg size 900,560 font 'Helvetica,13' background '#ffffff'
set output 'fig1_rinaldi_228.svg'
set grid lc rgb '#dddddd'
set key box opaque
set datafile missing 'NaN'
set title 'Rinaldi 228 alone, mu = 0.3 (study Fig. 3-4)'
set xlabel 'time (s)'
set ylabel 'sliding displacement u (mm)'
plot [0:12] 'p1_1d_engine.tsv' u 1:($2*1e3) w l lw 3 lc rgb '#1f77b4' t 'engine (Coulomb)', \
  'p1_1d_smooth.tsv' u 1:($2*1e3) w l lw 2 dt 2 lc rgb '#d62728' t 'smoothed (eta 20, U_y 1e-7 m)', \
  'p1_1d_plastic.tsv' u 1:($2*1e3) w l lw 2 dt 3 lc rgb '#2ca02c' t 'elastic-plastic'
