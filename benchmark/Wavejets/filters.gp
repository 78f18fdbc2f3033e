# gnuplot script written by bench_filters; run from this directory: gnuplot filters.gp
set terminal pngcairo size 1400,1000 font 'sans,11'
set output 'filters.png'
set multiplot layout 2,2
set logscale x
set xrange [1:20]
set xtics (1,1.5,2,3,4,5,6,8,10,12,15,20)
set xlabel 'detail wavelength lambda / Rf'
set grid
set key right top opaque box
set title 'wavejet\_enhance\_positions: detail gain (gain 2: solid, 3: dashed, -1: dotted, 0: dash-dot)'
set ylabel 'output / input amplitude'
set yrange [-3:5]
set arrow from 1,1 to 20,1 nohead lc rgb 'gray'
plot 'filters_positions.dat' u 1:6 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#1f77b4' t 'K 2', \
     'filters_positions.dat' u 1:8 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#1f77b4' notitle, \
     'filters_positions.dat' u 1:2 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#1f77b4' notitle, \
     'filters_positions.dat' u 1:4 w lp lw 2 pt 7 ps 0.6 dt 4 lc rgb '#1f77b4' notitle, \
     'filters_positions.dat' u 1:14 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#d62728' t 'K 4', \
     'filters_positions.dat' u 1:16 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#d62728' notitle, \
     'filters_positions.dat' u 1:10 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#d62728' notitle, \
     'filters_positions.dat' u 1:12 w lp lw 2 pt 7 ps 0.6 dt 4 lc rgb '#d62728' notitle, \
     'filters_positions.dat' u 1:22 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#2ca02c' t 'K 6', \
     'filters_positions.dat' u 1:24 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#2ca02c' notitle, \
     'filters_positions.dat' u 1:18 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#2ca02c' notitle, \
     'filters_positions.dat' u 1:20 w lp lw 2 pt 7 ps 0.6 dt 4 lc rgb '#2ca02c' notitle, \
     'filters_positions.dat' u 1:30 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#9467bd' t 'K 8', \
     'filters_positions.dat' u 1:32 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#9467bd' notitle, \
     'filters_positions.dat' u 1:26 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#9467bd' notitle, \
     'filters_positions.dat' u 1:28 w lp lw 2 pt 7 ps 0.6 dt 4 lc rgb '#9467bd' notitle
unset arrow
set title 'wavejet\_enhance\_positions: noise gain (residual RMS out / in; same lines)'
set ylabel 'output / input noise'
set logscale y
set yrange [0.1:10]
set ytics (0.1,0.2,0.5,1,1.25,2,5,10)
plot 'filters_positions.dat' u 1:7 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#1f77b4' t 'K 2', \
     'filters_positions.dat' u 1:9 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#1f77b4' notitle, \
     'filters_positions.dat' u 1:3 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#1f77b4' notitle, \
     'filters_positions.dat' u 1:5 w lp lw 2 pt 7 ps 0.6 dt 4 lc rgb '#1f77b4' notitle, \
     'filters_positions.dat' u 1:15 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#d62728' t 'K 4', \
     'filters_positions.dat' u 1:17 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#d62728' notitle, \
     'filters_positions.dat' u 1:11 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#d62728' notitle, \
     'filters_positions.dat' u 1:13 w lp lw 2 pt 7 ps 0.6 dt 4 lc rgb '#d62728' notitle, \
     'filters_positions.dat' u 1:23 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#2ca02c' t 'K 6', \
     'filters_positions.dat' u 1:25 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#2ca02c' notitle, \
     'filters_positions.dat' u 1:19 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#2ca02c' notitle, \
     'filters_positions.dat' u 1:21 w lp lw 2 pt 7 ps 0.6 dt 4 lc rgb '#2ca02c' notitle, \
     'filters_positions.dat' u 1:31 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#9467bd' t 'K 8', \
     'filters_positions.dat' u 1:33 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#9467bd' notitle, \
     'filters_positions.dat' u 1:27 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#9467bd' notitle, \
     'filters_positions.dat' u 1:29 w lp lw 2 pt 7 ps 0.6 dt 4 lc rgb '#9467bd' notitle
unset logscale y
set ytics auto
set title 'wavejet\_enhance\_normals: tilt detail gain, relative to gain 1 (same lines)'
set ylabel 'tilt amplitude / gain-1 tilt amplitude'
set yrange [-1.5:4]
set arrow from 1,1 to 20,1 nohead lc rgb 'gray'
plot 'filters_normals.dat' u 1:14 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#d62728' t 'K 4', \
     'filters_normals.dat' u 1:16 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#d62728' notitle, \
     'filters_normals.dat' u 1:10 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#d62728' notitle, \
     'filters_normals.dat' u 1:12 w lp lw 2 pt 7 ps 0.6 dt 4 lc rgb '#d62728' notitle, \
     'filters_normals.dat' u 1:22 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#2ca02c' t 'K 6', \
     'filters_normals.dat' u 1:24 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#2ca02c' notitle, \
     'filters_normals.dat' u 1:18 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#2ca02c' notitle, \
     'filters_normals.dat' u 1:20 w lp lw 2 pt 7 ps 0.6 dt 4 lc rgb '#2ca02c' notitle, \
     'filters_normals.dat' u 1:30 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#9467bd' t 'K 8', \
     'filters_normals.dat' u 1:32 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#9467bd' notitle, \
     'filters_normals.dat' u 1:26 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#9467bd' notitle, \
     'filters_normals.dat' u 1:28 w lp lw 2 pt 7 ps 0.6 dt 4 lc rgb '#9467bd' notitle
unset arrow
set title 'Noise gain at equal detail gain, gain 2 (WJ solid, H-USM dashed, J-USM dotted)'
set ylabel 'output / input noise'
set logscale y
set yrange [0.3:100]
set ytics (0.5,1,1.25,2,5,10,20,50,100)
plot 'filters_baselines.dat' u 1:2 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#1f77b4' t 'K 2', \
     'filters_baselines.dat' u 1:3 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#1f77b4' notitle, \
     'filters_baselines.dat' u 1:4 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#1f77b4' notitle, \
     'filters_baselines.dat' u 1:7 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#d62728' t 'K 4', \
     'filters_baselines.dat' u 1:8 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#d62728' notitle, \
     'filters_baselines.dat' u 1:9 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#d62728' notitle, \
     'filters_baselines.dat' u 1:12 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#2ca02c' t 'K 6', \
     'filters_baselines.dat' u 1:13 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#2ca02c' notitle, \
     'filters_baselines.dat' u 1:14 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#2ca02c' notitle, \
     'filters_baselines.dat' u 1:17 w lp lw 2 pt 7 ps 0.6 dt 1 lc rgb '#9467bd' t 'K 8', \
     'filters_baselines.dat' u 1:18 w lp lw 2 pt 7 ps 0.6 dt 2 lc rgb '#9467bd' notitle, \
     'filters_baselines.dat' u 1:19 w lp lw 2 pt 7 ps 0.6 dt 3 lc rgb '#9467bd' notitle
unset multiplot
