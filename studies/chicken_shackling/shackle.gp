# Step 4: one shackle run's histories (shackle-<case>.dat: displacements, the shackle's stress) as
# Fig 5-20 (rotating) or Fig 5-22 (inverting) of our FE model. Drawn by chicken_shackling.gp from the
# study's run (figures fig-5-20-fe-rotating-ramp, fig-5-22-fe-inverting-ramp), or by hand for a run
# of build/bin/chicken_shackling --shackle <case> ... (its files in build/results/chicken_shackling/shackle-<case>/):
#   gnuplot -e "dat='build/results/chicken_shackling/shackle-rotating/shackle-rotating.dat'; out='figures/fig-5-20-fe'" \
#     studies/chicken_shackling/shackle.gp
# Variables: dat, out (without extension), case ('rotating' default, or 'inverting'); term and ext
# (default pngcairo, png).
if (!exists("case")) case = 'rotating'
if (!exists("term")) term = 'pngcairo'
if (!exists("ext")) ext = 'png'
inverting = (case eq 'inverting')
reset  # settings only: the variables above stay
set terminal @term size 900,650 enhanced font 'sans,12' background rgb 'white'
set output out.'.'.ext
set multiplot layout 2,1 title (inverting ? 'Shackle inverting (Table 5-8), our FE model: displacements and the shackle stress (Fig 5-22)' : 'Shackle rotating (Table 5-8), our FE model: Fig 5-20 and the shackle stress')
set xlabel 't (s)'
set ylabel 'resultant displacement (mm)'
# The keys outside, right of each panel: inside they covered data (the thesis point's sample sat
# among the curves).
set key outside right top vertical Left reverse samplen 2 font ',10' spacing 1.2
set grid
stats dat u 1 nooutput
set xrange [0:STATS_max]  # both panels over the run's window
set lmargin at screen 0.09
set rmargin at screen 0.70  # both panels' axes aligned, the keys right of them
# The drive stops at Table 5-8's operation time.
set arrow 1 from 0.116, graph 0 to 0.116, graph 1 nohead dt 3 lc rgb 'gray40'
plot dat u 1:2 w l lw 2 t 'chicken centre', \
     dat u 1:3 w l lw 2 t 'shackle centre point', \
     dat u 1:4 w l lw 1 t 'paws (mean)', \
     dat u 1:(-$5) w l lw 2 dt 2 t 'shackle point - chicken', \
     '+' u (0.12):(inverting ? NaN : 95) w p pt 7 ps 1.5 lc rgb 'black' t (inverting ? '' : 'thesis: 9.5 cm at 0.12 s')
set ylabel 'shackle von Mises (MPa)'
plot dat u 1:7 w l lw 1.5 t 'largest (1 ms samples)', \
     (inverting ? 78.5 : 25) w l dt 2 lc rgb 'black' t (inverting ? 'thesis: 78.5 MPa' : 'thesis: 25 MPa')
unset multiplot
unset arrow 1
