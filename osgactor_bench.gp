set terminal pngcairo size 1100,520 font 'sans,10' noenhanced
set output './osgactor_bench.png'
set logscale xy
set grid
set key below
set xrange [0.7:1500]
set yrange [0.5:5000]
set xlabel 'actors (31 joints each)'
set ylabel 'ns per joint'
set multiplot layout 1,2
set title 'update'
plot './osgactor_bench_plot.dat' index 0 using 1:2 with linespoints title 'osgActor_all', './osgactor_bench_plot.dat' index 1 using 1:2 with linespoints title 'osgActor_quarter', './osgactor_bench_plot.dat' index 2 using 1:2 with linespoints title 'osgActor_idle', './osgactor_bench_plot.dat' index 3 using 1:2 with linespoints title 'osgAnimation', './osgactor_bench_plot.dat' index 4 using 1:2 with linespoints title 'plainOSG'
set title 'update_cull'
plot './osgactor_bench_plot.dat' index 5 using 1:2 with linespoints title 'osgActor_all', './osgactor_bench_plot.dat' index 6 using 1:2 with linespoints title 'osgActor_quarter', './osgactor_bench_plot.dat' index 7 using 1:2 with linespoints title 'osgActor_idle', './osgactor_bench_plot.dat' index 8 using 1:2 with linespoints title 'osgAnimation', './osgactor_bench_plot.dat' index 9 using 1:2 with linespoints title 'plainOSG'
unset multiplot
