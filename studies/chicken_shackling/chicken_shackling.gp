# Figures of study chicken_shackling. Variables set by the study: results (data folder), figures
# (output folder), term (gnuplot terminal: svg or pngcairo) and ext (file extension).
set datafile commentschars '#'

# --- Fig 5-1 / Fig 5-19: the birds as meshed (surface of the tet10 mesh, bird frame, mm) -------------
# The data hold one pm3d block per surface triangle with a Lambert shade (io/surface_plot.hpp); the
# bird's y (up) is drawn as gnuplot's z, its z (lateral) as gnuplot's y.
set palette defined (0 '#3b2a1c', 0.5 '#a8805a', 1 '#f3dcb4')
set cbrange [0:1]
unset colorbox
set pm3d depthorder corners2color c1 border lc rgb '#40000000' lw 0.3

set terminal @term size 900,650 enhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-5-1-bird.'.ext
set title "Fig 5-1  Half model of the Table 5-1 chicken (10-node tetrahedra, surface), symmetry plane z = 0\nleg: paw J1 - L1 - hinge J2 - L2 - hinge J3 - L3 - hip J4 in a groove of the body; head toward -x"
set view equal xyz
set view 68, 205, 1.7
unset border
unset tics
unset key
splot results.'/bird-half-5-1.dat' using 1:3:2:4 with pm3d

set output figures.'/fig-5-19-bird.'.ext
set title "Fig 5-19 (bird)  Full model of the Table 5-3 chicken for the shackle\nL = 371.5 mm; legs L1 75 / 30 mm and L2 70 / 30 mm, L3 omitted; seen from below the left flank"
set view 100, 240, 2.0
splot results.'/bird-full-5-3.dat' using 1:3:2:4 with pm3d
reset

# --- Fig 5-2: side view of the construction: outlines, limbs, hinges, hip bricks, joints ------------------
set terminal @term size 900,650 enhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-5-2-skeleton.'.ext
set multiplot layout 2,1 title 'Fig 5-2  Side view of the reconstructed birds (bird frame, mm): Table 5-1 (top), Table 5-3 (bottom)'
set size ratio -1
set grid
set xlabel 'x (mm)'
set ylabel 'y (mm)'
unset key
set xrange [-290:110]
set yrange [-80:65]
plot results.'/side-5-1.dat' using 1:2 with lines lw 1.5 lc rgb '#8c564b', \
     results.'/joints-5-1.dat' using 1:2 with points pt 7 ps 0.8 lc rgb '#d62728', \
     '' using 1:2:3 with labels offset 1.2,0.8 font ',10'
plot results.'/side-5-3.dat' using 1:2 with lines lw 1.5 lc rgb '#8c564b', \
     results.'/joints-5-3.dat' using 1:2 with points pt 7 ps 0.8 lc rgb '#d62728', \
     '' using 1:2:3 with labels offset 1.2,0.8 font ',10'
unset multiplot
reset

# --- Fig 5-3 / Table 5-2: force-displacement of each limb -------------------------------------------------
set terminal @term size 900,650 enhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-5-3-limbs.'.ext
set multiplot layout 1,3 title "Table 5-2  Each limb alone: thesis (ANSYS SOLID92) and ours (tet10, dynamic relaxation, calibrated widths)"
set grid
set key bottom right font ',10'
set xlabel 'd of the loaded joint (mm)'
set xrange [0:*]
set yrange [0:*]
set ylabel 'force (N)'
steps = '10 4 2'
do for [i=1:3] {
    set title sprintf('limb %d', i)
    set xtics word(steps, i) + 0
    if (i < 3) {
        plot results.'/limb-'.i.'.dat' using 2:1 with linespoints pt 7 lw 2 lc rgb '#d62728' title 'thesis', \
             '' using 3:1 with linespoints pt 5 lw 2 lc rgb '#1f77b4' title 'ours', \
             '' using 4:1 with lines dt 2 lw 1.5 lc rgb '#7f7f7f' title 'ours, linear'
    } else {
        plot results.'/limb-'.i.'.dat' using 2:1 with linespoints pt 7 lw 2 lc rgb '#d62728' title 'thesis', \
             '' using 3:1 with linespoints pt 5 lw 2 lc rgb '#1f77b4' title 'ours', \
             '' using 4:1 with lines dt 2 lw 1.5 lc rgb '#7f7f7f' title 'ours, linear', \
             results.'/limb-3-reversed.dat' using 2:1 with linespoints pt 4 lw 1.5 lc rgb '#2ca02c' title 'ours, fixed at J3'
    }
}
unset multiplot
reset

# --- Figs 5-24/5-25: the Lagrange bird's body-centre displacement --------------------------------------
set terminal @term size 900,650 enhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-5-24-25-lagrange.'.ext
set multiplot layout 2,2 title "Figs 5-24/5-25  Body-centre displacement of the 2-D Lagrange bird (our reconstruction; Table 5-2 springs)"
set grid
set key top left font ',10'
set offsets 0, 0, graph 0.4, 0
set xlabel 't (s)'
set ylabel '|displacement| (mm)'
set style fill transparent solid 0.25 noborder
do for [c in 'rotating inverting'] {
    set title 'shackle '.c.' (Table 5-8; operation 0-0.116 s)'
    plot results.'/lagrange-'.c.'.dat' using 1:3:4 with filledcurves lc rgb '#1f77b4' title 'springs x0.5..x2', \
         '' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'nominal, undamped', \
         '' using 1:5 with lines lw 2 dt 2 lc rgb '#d62728' title 'alpha = 100 1/s'
}
set offsets 0, 0, 0, 0
set size ratio -1
set xlabel 'x (mm)'
set ylabel 'y (mm)'
set xtics 100
set ytics 50
set cblabel 'snapshot (x 50 ms)'
unset key
do for [c in 'rotating inverting'] {
    set title 'chain paw - J2 - body centre every 50 ms ('.c.')'
    plot results.'/lagrange-'.c.'-chain.dat' using 1:2:(column(-2)) with linespoints pt 7 ps 0.6 lw 1 lc palette notitle
}
unset multiplot

# --- Figs 5-20 / 5-22 of our FE shackle model (Step 4; 5 ms drive ramp, reconstruction 19) ------------
here = system('dirname '.ARG0)
dat = results.'/shackle-rotating.dat'; out = figures.'/fig-5-20-fe-rotating-ramp'; case = 'rotating'
load here.'/shackle.gp'
reset
dat = results.'/shackle-inverting.dat'; out = figures.'/fig-5-22-fe-inverting-ramp'; case = 'inverting'
load here.'/shackle.gp'
reset
