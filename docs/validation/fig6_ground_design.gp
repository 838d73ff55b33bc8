# fig6_ground_design.gp - drawn by 'seislide study'; run in this folder: gnuplot fig6_ground_design.gp
set terminal svg size 900,560 font 'Helvetica,13' background '#ffffff'
set output 'fig6_ground_design.svg'
set grid lc rgb '#dddddd'
set key box opaque
set datafile missing 'NaN'
set multiplot layout 2,2 title 'Ground set matched to RG 1.60: design sliding spectra'
set logscale y
set format y '%g'
set xlabel 'mu g / PGA'
set ylabel 'design displacement (mm)'
set key top right font ',10'
do for [a in '0.2 0.4 0.6 0.8'] {
  f = sprintf('p3_ground_%sg.tsv', a)
  set title sprintf('PGA %s g', a)
  plot [0:1] f u 2:($5*1e3) w l lw 2 t 'NLTHA 3.0 x mean', f u 2:($6*1e3) w l lw 2 t 'ASCE 2.0 x best', \
    f u 2:($7*1e3) w l dt 2 lc rgb '#777777' t '1.5 x PGD cap'
}
unset multiplot
