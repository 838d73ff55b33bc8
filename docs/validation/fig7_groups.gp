# fig7_groups.gp - drawn by 'seislide study'; run in this folder: gnuplot fig7_groups.gp
set terminal svg size 900,560 font 'Helvetica,13' background '#ffffff'
set output 'fig7_groups.svg'
set grid lc rgb '#dddddd'
set key box opaque
set datafile missing 'NaN'
set multiplot layout 2,2 title 'Real record groups: best-estimate (thin) and design (thick) sliding spectra'
set logscale y
set format y '%g'
set yrange [0.1:*]
set xlabel 'mu'
set ylabel 'displacement (mm)'
set key top right font ',9'
do for [g in 'nfsoil ffsoil nfrock pulse'] {
  f = sprintf('p4_%s.tsv', g)
  set title (g eq 'nfsoil' ? 'near-field soil' : g eq 'ffsoil' ? 'far-field soil' : g eq 'nfrock' ? 'near-field rock' : 'pulse-like')
  plot [0:0.8] f u 1:($3*1e3) w l lw 1 lc rgb '#1f77b4' t 'NLTHA mean', \
    f u 1:($4*1e3) w l lw 1 lc rgb '#d62728' t 'ASCE best', \
    f u 1:($5*1e3) w l lw 3 lc rgb '#1f77b4' t 'NLTHA design', \
    f u 1:($6*1e3) w l lw 3 lc rgb '#d62728' t 'ASCE design'
}
unset multiplot
