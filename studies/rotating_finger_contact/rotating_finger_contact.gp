# Figures of study rotating_finger_contact. Variables set by the study: results (data folder),
# figures (output folder), term (gnuplot terminal: svg or pngcairo) and ext (file extension).
set datafile commentschars '#'
set datafile missing 'nan'
set grid

# Fig 3-21: reaction force on the object (2 ms means), general case.
set terminal @term size 900,500 enhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-3-21.'.ext
set title 'Fig 3-21  Reaction force on the object (alpha 7.5 1/s, rigid object)'
set xlabel 'time (s)'
set ylabel 'force (N)'
plot results.'/case-alpha-7.5.dat' using 1:2 with lines lw 1.5 title '|F| (2 ms means)'

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
     results.'/fig-3-20.dat' using 1:2 with lines lc rgb '#1f77b4' title 'finger'
unset parametric
set size noratio

# Figs 3-23..3-25: effect of the finger damping coefficient.
set size noratio
set xlabel 'time (s)'
do for [q in 'finger object force'] {
    col = (q eq 'finger') ? 5 : (q eq 'object') ? 6 : 2
    num = (q eq 'finger') ? '23' : (q eq 'object') ? '24' : '25'
    set output figures.'/fig-3-'.num.'.'.ext
    set title 'Fig 3-'.num.'  Effect of alpha on the '.((q eq 'force') ? 'reaction force' : 'max '.q.' stress')
    set ylabel (q eq 'force') ? 'force (N)' : 'max von Mises stress (MPa)'
    plot results.'/case-alpha-7.5.dat' using 1:col with lines lw 1.5 title 'alpha 7.5', \
         results.'/case-alpha-180.dat' using 1:col with lines lw 1.5 title 'alpha 180', \
         results.'/case-alpha-600.dat' using 1:col with lines lw 1.5 title 'alpha 600'
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
