# Figures of study rotating_finger_contact. Variables set by the study: results (data folder),
# figures (output folder), term (gnuplot terminal: svg or pngcairo) and ext (file extension).
set datafile commentschars '#'
set datafile missing 'nan'
set grid

# Columns of case-<name>.dat: 1 t, 2 |F| CFC 60, 3 Fx, 4 Fy, 5 finger stress (CFC 60), 6 object stress (CFC 60),
# 7-8 contact point, 9 |F| 2 ms means, 10 contact force, 11-12 raw stress maxima over 2 ms.

# Fig 3-21: reaction force at the sensor, general case.
set terminal @term size 900,500 enhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-3-21.'.ext
set title 'Fig 3-21  Reaction force at the sensor (alpha 7.5 1/s, aluminium object)'
set xlabel 'time (s)'
set ylabel 'force (N)'
plot results.'/case-alpha-7.5.dat' using 1:9 with lines lc rgb '#bbbbbb' title '|F|, 2 ms means', \
     results.'/case-alpha-7.5.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title '|F|, SAE J211 CFC 60', \
     results.'/case-alpha-7.5.dat' using 1:10 with lines lw 1 dt 2 lc rgb '#d62728' title 'contact force (2 ms means)'

# Fig 3-22: contact location (force-weighted centroid) on the object.
set output figures.'/fig-3-22.'.ext
set title 'Fig 3-22  Contact location on the elliptical object'
set xlabel 'x (mm)'
set ylabel 'y (mm)'
set size ratio -1
set parametric
set trange [0:2*pi]
plot 101.6+99.1*cos(t), 184.15+67.3*sin(t) with lines lc rgb 'black' title 'object', \
     results.'/case-alpha-7.5.dat' using 7:8 with points pt 7 ps 0.4 title 'E_{object} 69 GPa', results.'/case-E-object-6.1MPa.dat' using 7:8 with points pt 6 ps 0.4 title 'E_{object} 6.1 MPa'
unset parametric
set size noratio

# Fig 3-20: finger outlines at several instants (every 0.05 s), object and drum.
set output figures.'/fig-3-20.'.ext
set title 'Fig 3-20  Finger outline every 0.05 s (general case)'
set size ratio -1
set parametric
plot 101.6+99.1*cos(t), 184.15+67.3*sin(t) with lines lc rgb 'black' lw 2 title 'object', \
     82.55*cos(t), 82.55*sin(t) with lines lc rgb 'gray' title 'drum', \
     results.'/outline-alpha-7.5.dat' using 1:2 with lines lc rgb '#1f77b4' title 'finger'
unset parametric
set size noratio

# Figs 3-26..3-29: deformed shapes for alpha 1, 7.5, 180 and 600 (outlines every 0.05 s).
set output figures.'/fig-3-26-29.'.ext
set terminal @term size 1000,900 enhanced font 'sans,11' background rgb 'white'
set multiplot layout 2,2 title 'Figs 3-26..3-29  Finger outlines every 0.05 s'
set size ratio -1
set parametric
unset key
do for [a in '1 7.5 180 600'] {
    set title 'alpha '.a.' 1/s'
    plot 101.6+99.1*cos(t), 184.15+67.3*sin(t) with lines lc rgb 'black' lw 2, \
         82.55*cos(t), 82.55*sin(t) with lines lc rgb 'gray', \
         results.'/outline-alpha-'.a.'.dat' using 1:2 with lines lc rgb '#1f77b4'
}
unset multiplot
unset parametric
set key
set size noratio
set terminal @term size 900,500 enhanced font 'sans,12' background rgb 'white'

# Fig 3-30: contact start and end for each alpha (contact force above 2 % of its maximum).
set output figures.'/fig-3-30.'.ext
set title 'Fig 3-30  Contact interval vs alpha (E_{finger} 6.1 MPa, aluminium object)'
set xlabel 'time (s)'
set ylabel 'alpha (1/s)'
set logscale y
set yrange [0.5:1000]
plot results.'/contact-instants.dat' using 2:1:2:3:1:1 with xyerrorbars lw 2 pt 7 title 'contact start .. end'
unset logscale y
set autoscale y

# Figs 3-23..3-25: effect of the finger damping coefficient.
set size noratio
set xlabel 'time (s)'
do for [q in 'finger object force'] {
    col = (q eq 'finger') ? 5 : (q eq 'object') ? 6 : 2
    num = (q eq 'finger') ? '23' : (q eq 'object') ? '24' : '25'
    set output figures.'/fig-3-'.num.'.'.ext
    set title 'Fig 3-'.num.'  Effect of alpha on the '.((q eq 'force') ? 'reaction force' : 'max '.q.' stress')
    set ylabel (q eq 'force') ? 'force (N)' : 'max von Mises stress (MPa)'
    plot for [a in '1 7.5 20 50 180 600'] results.'/case-alpha-'.a.'.dat' using 1:col with lines lw 1.5 title 'alpha '.a
}

# Figs 3-31..3-33 and 3-34..3-36: finger and object modulus (three panels each).
do for [v in 'finger object'] {
    other = (v eq 'finger') ? 'E-finger-4.2' : 'E-object-6.1MPa'
    lab = (v eq 'finger') ? 'E_{finger} 4.2 MPa' : 'E_{object} 6.1 MPa'
    set output figures.'/fig-3-'.((v eq 'finger') ? '31-33' : '34-36').'.'.ext
    set multiplot layout 3,1 title 'Effect of E_{'.v.'} (Figs '.((v eq 'finger') ? '3-31..3-33' : '3-34..3-36').')'
    unset title
    set ylabel 'finger (MPa)'
    plot results.'/case-alpha-7.5.dat' using 1:5 with lines title 'general case', results.'/case-'.other.'.dat' using 1:5 with lines title lab
    set ylabel 'object (MPa)'
    plot results.'/case-alpha-7.5.dat' using 1:6 with lines title 'general case', results.'/case-'.other.'.dat' using 1:6 with lines title lab
    set ylabel 'force (N)'
    plot results.'/case-alpha-7.5.dat' using 1:2 with lines title 'general case', results.'/case-'.other.'.dat' using 1:2 with lines title lab
    unset multiplot
}
