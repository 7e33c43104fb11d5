# Figures of study finger_damping. Variables set by the study: results (data folder), figures (output
# folder), term (gnuplot terminal: svg or pngcairo) and ext (file extension).
set datafile commentschars '#'
set grid

# Fig 3-3: first ten modes of the 8-inch finger: frequencies and the classifier's energy fractions.
set terminal @term size 900,650 enhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-3-3.'.ext
set multiplot layout 2,1 title 'Fig 3-3  First ten modes of the 8-inch finger (tet10), classified by rigid-section fits'
set xlabel 'mode'
set ylabel 'frequency (Hz)'
set xrange [0.5:10.5]
set xtics 1
set logscale y
plot results.'/fig-3-3.dat' using 1:2 with linespoints lw 2 pt 7 lc rgb '#1f77b4' notitle
unset logscale y
set ylabel 'fraction of sum m |u|^2'
set yrange [0:1.05]
set xrange [-0.6:9.6]
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.7
set key outside right
plot results.'/fig-3-3.dat' using 3:xtic(1) title 'bending' lc rgb '#1f77b4', \
     '' using 4 title 'torsion' lc rgb '#d62728', \
     '' using 5 title 'elongation' lc rgb '#2ca02c', \
     '' using 6 title 'other' lc rgb '#7f7f7f'
unset multiplot
set style data lines
set autoscale
unset xrange
unset yrange
set xtics autofreq
set key default

# Figs 3-5 and 3-6: the four modelling cases of Table 3-2 under the tip impulse, alpha = 180 1/s.
# Case A runs the thesis's 0.2 s, B and C 30 ms, D 1 ms by default (cost; --full, i.e. make all, runs
# it to 65 ms): the lower panels zoom on the first 30 ms, where all four can be compared.
stats results.'/fig-3-5-D.dat' using 1 nooutput
d_end = STATS_max
titleA = 'Case A (5 x 5 mapped hex8, 725)'
titleB = 'Case B (9 x 9 mapped hex8, 4698; 30 ms)'
titleC = 'Case C (Gmsh tet10, 4676; 30 ms)'
titleD = sprintf('Case D (reconstructed detailed, tet10, 16633; %.0f ms)', d_end)
set terminal @term size 900,900 enhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-3-5.'.ext
set multiplot layout 2,1 title 'Fig 3-5  Tip response of the 4.5-inch finger to a tip impulse, alpha = 180 1/s'
set xlabel 'time (ms)'
set ylabel 'tip deflection (mm)'
set key top right
do for [panel=1:2] {
    if (panel == 1) { set xrange [0:200] } else { set xrange [0:30]; set key bottom center }
    plot results.'/fig-3-5-A.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title titleA, \
         results.'/fig-3-5-B.dat' using 1:2 with lines lw 2 dt 2 lc rgb '#d62728' title titleB, \
         results.'/fig-3-5-C.dat' using 1:2 with lines lw 2 dt 4 lc rgb '#2ca02c' title titleC, \
         results.'/fig-3-5-D.dat' using 1:2 with lines lw 3 lc rgb '#000000' title titleD
}
unset multiplot
set key default

set output figures.'/fig-3-6.'.ext
set multiplot layout 2,1 title 'Fig 3-6  Maximum equivalent (von Mises) stress of the finger, alpha = 180 1/s'
set ylabel 'max von Mises stress (MPa)'
do for [panel=1:2] {
    if (panel == 1) { set xrange [0:200] } else { set xrange [0:30] }
    plot results.'/fig-3-6-A.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'Case A', \
         results.'/fig-3-6-B.dat' using 1:2 with lines lw 2 dt 2 lc rgb '#d62728' title 'Case B', \
         results.'/fig-3-6-C.dat' using 1:2 with lines lw 2 dt 4 lc rgb '#2ca02c' title 'Case C', \
         results.'/fig-3-6-D.dat' using 1:2 with lines lw 3 lc rgb '#000000' title 'Case D'
}
unset multiplot
unset xrange
set autoscale

# Figs 3-11..3-14: tip responses of each finger under the trial alphas of the alpha_cr search.
set terminal @term size 1100,800 enhanced font 'sans,11' background rgb 'white'
set output figures.'/fig-3-11.'.ext
set multiplot layout 2,2 title 'Figs 3-11..3-14  Tip responses under the trial alphas of the automated alpha_{cr} search'
set key top right font 'sans,8'
set ylabel 'tip deflection (mm)'
do for [L in '3 4.5 6 8'] {
    f = results.'/fig-3-11-'.L.'in.dat'
    stats f using 1 nooutput
    set title L.'-inch finger'
    plot for [k=0:STATS_blocks-1] f index k using 1:2 with lines lw 1.5 title columnheader(2)
}
unset multiplot
set key default

# Fig 3-15: trial matching on a curve of known alpha (180 1/s).
set terminal @term size 900,560 enhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-3-15.'.ext
set title 'Fig 3-15  Trial matching: target computed at alpha = 180 1/s, extreme trials of the search'
set ylabel 'tip deflection (mm)'
set key autotitle columnhead
plot results.'/fig-3-15.dat' using 1:2 with lines lw 3 lc rgb '#000000' title 'target (alpha 180)', \
     '' using 1:3 with lines lw 1.5 lc rgb '#1f77b4' title 'lowest trial alpha', \
     '' using 1:4 with lines lw 1.5 lc rgb '#d62728' title 'highest trial alpha'
set key noautotitle

# Fig 3-16: damping ratio versus finger length (Eq 3-1).
set output figures.'/fig-3-16.'.ext
set title 'Fig 3-16  Damping ratio versus finger length (Table 3-3, Eq 3-1)'
set xlabel 'finger length (inch)'
set ylabel 'zeta'
plot results.'/eq-3-1-3-3.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'Eq 3-1 as printed', \
     results.'/table-3-3-thesis.dat' using 1:2 with points pt 7 ps 1.5 lc rgb '#d62728' title 'Table 3-3 zeta column', \
     '' using 1:3 with points pt 6 ps 2 lc rgb '#000000' title 'alpha / alpha_{cr} (what Eq 3-1 fits)'

# Fig 3-17: damping coefficients versus finger length (Eqs 3-2, 3-3), with our alpha_cr.
set output figures.'/fig-3-17.'.ext
set title 'Fig 3-17  Damping coefficients versus finger length (Table 3-3, Eqs 3-2, 3-3)'
set ylabel 'alpha, alpha_{cr} (1/s)'
set logscale y
plot results.'/eq-3-1-3-3.dat' using 1:3 with lines lw 2 lc rgb '#2ca02c' title 'alpha, Eq 3-2', \
     '' using 1:4 with lines lw 2 lc rgb '#1f77b4' title 'alpha_{cr}, Eq 3-3', \
     results.'/table-3-3-thesis.dat' using 1:4 with points pt 7 ps 1.5 lc rgb '#2ca02c' title 'alpha, Table 3-3', \
     '' using 1:5 with points pt 7 ps 1.5 lc rgb '#1f77b4' title 'alpha_{cr}, Table 3-3', \
     results.'/fig-3-17.dat' using 1:2 with linespoints pt 5 ps 1.5 lw 1 lc rgb '#d62728' title 'alpha_{cr}, our search (explicit FE)', \
     '' using 1:3 with linespoints pt 4 ps 1.5 dt 2 lc rgb '#9467bd' title '2 omega_1, FE modal', \
     '' using 1:4 with lines dt 3 lw 2 lc rgb '#7f7f7f' title '2 omega_1, Euler-Bernoulli'
unset logscale y
