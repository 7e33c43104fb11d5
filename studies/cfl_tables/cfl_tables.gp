# Figures of study cfl_tables. Variables set by the study: results (data folder), figures (output
# folder), term (gnuplot terminal: svg or pngcairo) and ext (file extension).
set terminal @term size 900,650 enhanced font 'sans,12' background rgb 'white'
set datafile commentschars '#'
set grid

# Fig 2-6: critical time step of the quadrangular shell versus E, rho, L_e and nu (Table 2-3).
set output figures.'/fig-2-6.'.ext
set multiplot layout 2,2 title 'Fig 2-6  Critical time step of a quadrangular shell element (Table 2-1, Table 2-3)'
set ylabel 'critical time step (us)'
set xlabel 'elastic modulus E (GPa)'
plot results.'/fig-2-6-E_GPa.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'rho 2700, L_e 10 mm, nu 0.3'
set xlabel 'density rho (kg/m^3)'
set xtics 1000
plot results.'/fig-2-6-rho.dat' using 1:2 with lines lw 2 lc rgb '#d62728' title 'E 70 GPa, L_e 10 mm, nu 0.3'
set xlabel 'characteristic length L_e (mm)'
set xtics autofreq
plot results.'/fig-2-6-L_mm.dat' using 1:2 with lines lw 2 lc rgb '#2ca02c' title 'E 70 GPa, rho 2700, nu 0.3'
set xlabel 'Poisson ratio nu'
plot results.'/fig-2-6-nu.dat' using 1:2 with lines lw 2 lc rgb '#9467bd' title 'E 70 GPa, rho 2700, L_e 10 mm'
unset multiplot

# Fig 2-5: the three shell elements of Table 2-2 (outlines in mm).
set terminal @term size 900,360 enhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-2-5.'.ext
set title 'Fig 2-5  Elements of Table 2-2: triangle, Quad 1, Quad 2 (AL6061)'
unset grid
set size ratio -1
set xrange [-2:42]
set yrange [-3:13]
set xlabel 'x (mm)'
set ylabel 'y (mm)'
set label 1 'triangle: L_e 7.07 mm, dt 1.32 us' at 0,-1.8 font 'sans,10'
set label 2 'Quad 1: L_e 10 mm, dt 1.87 us' at 15,-1.8 font 'sans,10'
set label 3 'Quad 2: L_e 5 mm, dt 0.93 us' at 30,-1.8 font 'sans,10'
plot for [k=0:2] results.'/fig-2-5.dat' using 1:($3 == k ? $2 : 1/0) with linespoints lw 2 pt 7 lc k+1 notitle
unset label
set size noratio
set autoscale

# Eq 2-25: highest frequency of an n-element AL6061 rod over 2 c_w / L_e.
set terminal @term size 760,480 enhanced font 'sans,12' background rgb 'white'
set output figures.'/eq-2-25.'.ext
set title 'Eq 2-25  omega_{max} of an n-element rod (10 mm elements) / (2 c_w / L_e)'
set grid
set logscale x 2
set xlabel 'number of elements n'
set ylabel 'omega_{max} L_e / (2 c_w)'
set yrange [0.6:1.9]
set key bottom right
plot results.'/eq-2-25.dat' using 1:2 with linespoints lw 2 pt 7 title 'lumped mass, free-free (Eq 2-24: exactly 1)', \
     '' using 1:3 with linespoints lw 2 pt 5 title 'lumped mass, one end fixed', \
     '' using 1:4 with linespoints lw 2 pt 9 title 'consistent mass, free-free (sqrt 3 = 1.732)'
