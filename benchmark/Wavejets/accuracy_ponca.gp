# Plot of accuracy_ponca.dat (written by bench_ponca_accuracy); run from this directory: gnuplot accuracy_ponca.gp
# Columns: surface noise k, then one per estimator: 4 CGAL-2, 7 WJ-2, 9 WJ-4, 10 WJH-2, 12 WJH-4, 15 WJH-2-w10, 20 APSS, 22 ASO-s.
set terminal pngcairo size 1800,1000 font 'DejaVu Sans,11'
set output 'accuracy_ponca.png'
set multiplot layout 2,4 title 'Relative RMSE of H against the number of neighbors k (same neighborhoods for every estimator)'
set termoption noenhanced
set logscale xy
set format y '%.0e'
set xtics (20, 50, 100, 200)
set xrange [15:260]
set grid
set key font ',9'
set xlabel 'k'
do for [s in "torus ellipsoid"] {
  do for [n in "0 0.25 0.5 1"] {
    set title s.', noise '.n.'%'
    # one legend, in an empty corner of one panel: the curves are the same in every panel
    if (s eq "ellipsoid" && n eq "0.25") { set key bottom left Left reverse samplen 2 } else { unset key }
    f = sprintf("< awk '$1==\"%s\" && $2==%s' accuracy_ponca.dat", s, n)
    plot f using 3:4 w lp lw 2 pt 4 dt 3 title 'CGAL jets 2', \
         f using 3:7 w lp lw 2 pt 7 title 'WJ-2', \
         f using 3:9 w lp lw 2 pt 5 title 'WJ-4', \
         f using 3:10 w lp lw 2 pt 9 title 'WJH-2 (Hermite)', \
         f using 3:12 w lp lw 2 pt 11 title 'WJH-4 (Hermite)', \
         f using 3:15 w lp lw 2 pt 13 title 'WJH-2, weight 10', \
         f using 3:($20 > 0 ? $20 : 1/0) w lp lw 2 pt 6 dt 2 title 'Ponca APSS', \
         f using 3:($22 > 0 ? $22 : 1/0) w lp lw 2 pt 8 dt 4 title 'Ponca ASO-s'
  }
}
unset multiplot
