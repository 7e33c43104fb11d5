# Figures of study finger_twist. Variables set by the study: results (data folder), figures (output
# folder), term (gnuplot terminal: svg or pngcairo) and ext (file extension).
set terminal @term size 900,560 enhanced font 'sans,12' background rgb 'white'
set datafile commentschars '#'
set grid

# Fig 3-41: twist angle of the tip versus time.
set output figures.'/fig-3-41.'.ext
set title 'Fig 3-41  Twist angle of the 4.5-inch finger under a suddenly applied 2 x 4.45 N couple (alpha = 180 1/s)'
set xlabel 'time (ms)'
set ylabel 'twist angle (deg)'
set key bottom right
set xrange [0:60]
plot results.'/fig-3-41.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'Case A, tip-face rotation', \
     '' using 1:3 with lines lw 1 dt 2 lc rgb '#1f77b4' title 'Case A, line through the loading points', \
     '' using 1:4 with lines lw 2 lc rgb '#d62728' title 'refined O-grid, tip-face rotation', \
     '' using 1:5 with lines lw 1 dt 3 lc rgb '#000000' title 'Saint-Venant static (Case A couple)', \
     25.5 with lines lw 1 dt 4 lc rgb '#2ca02c' title 'thesis: max 25.5 deg (simulation)'

# Fig 3-40: displacements of the two loading points.
set output figures.'/fig-3-40.'.ext
set title 'Fig 3-40  Displacements of the loading points (Case A)'
set ylabel 'displacement (mm)'
set key top right
plot results.'/fig-3-40.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'point (0, +b): u_x', \
     '' using 1:3 with lines lw 2 dt 2 lc rgb '#1f77b4' title 'point (0, +b): u_y', \
     '' using 1:4 with lines lw 2 lc rgb '#d62728' title 'point (0, -b): u_x', \
     '' using 1:5 with lines lw 2 dt 2 lc rgb '#d62728' title 'point (0, -b): u_y'
