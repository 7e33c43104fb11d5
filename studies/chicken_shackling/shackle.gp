# Step 4 (run alone, not by the study): Fig 5-20 of our shackle FE model from the histories that
#   build/bin/chicken_shackling --shackle rotating <end>
# writes (shackle-rotating.dat). Usage:
#   gnuplot -e "dat='shackle-rotating.dat'; out='figures/fig-5-20-fe'" studies/chicken_shackling/shackle.gp
# and with case='inverting' for the inverting run (Fig 5-22's stress, 78.5 MPa).
if (!exists("case")) case = 'rotating'
inverting = (case eq 'inverting')
set terminal pngcairo size 900,650 enhanced font 'sans,12' background rgb 'white'
set output out.'.png'
set multiplot layout 2,1 title (inverting ? 'Shackle inverting (Table 5-8), our FE model: displacements and the shackle stress (Fig 5-22)' : 'Shackle rotating (Table 5-8), our FE model: Fig 5-20 and the shackle stress')
set xlabel 't (s)'
set ylabel 'resultant displacement (mm)'
set key top left
set grid
set arrow from 0.116, graph 0 to 0.116, graph 1 nohead dt 3 lc rgb 'gray40'
plot dat u 1:2 w l lw 2 t 'chicken centre', \
     dat u 1:3 w l lw 2 t 'shackle centre point', \
     dat u 1:4 w l lw 1 t 'paws (mean)', \
     dat u 1:(-$5) w l lw 2 dt 2 t '|relative| (shackle - chicken)', \
     '+' u (0.12):(inverting ? NaN : 95) w p pt 7 ps 1.5 lc rgb 'black' t (inverting ? '' : 'thesis: largest relative 9.5 cm at 0.12 s')
set ylabel 'shackle von Mises (MPa)'
plot dat u 1:7 w l lw 1.5 t 'largest element von Mises in the shackle (sampled every 1 ms)', \
     (inverting ? 78.5 : 25) w l dt 2 lc rgb 'black' t (inverting ? 'thesis: 78.5 MPa' : 'thesis: 25 MPa')
unset multiplot
