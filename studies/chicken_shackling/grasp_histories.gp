# Step 3 histories of one case (Figs 5-11, 5-13..5-15 of the thesis), from the record
# `chicken_shackling --grasp <case>` writes (grasp-case-<n>.dat: t, body x y z, perch x y, paw x y z,
# theta_b, tip dy A..E, von Mises A..E, fingers-on-bird force). Run from the project root:
#   gnuplot -e "data='build/results/chicken_shackling/grasp-case-4/grasp-case-4.dat'; out='h.png'; label='...'" \
#     studies/chicken_shackling/grasp_histories.gp
# The thesis's printed Case 4 values are marked (+): theta_b 24.5 deg at 0.88 s and -60 deg at 1.1 s,
# finger E's tip 70.3 mm at 0.94 s (drawn at -70.3: the tip moves down), 2.85 MPa at 0.97 s.
set terminal pngcairo size 1400,1000 enhanced font 'sans,11' background rgb 'white'
set output out
set multiplot layout 2,2 title label
set key top left font ',9'
set grid
set xlabel 't [s]'
set title 'body centre and perch top (Fig 5-11), x and y [mm]'
set ylabel 'mm'
plot data u 1:2 w l lw 2 t 'body x', data u 1:3 w l lw 2 t 'body y', \
     data u 1:5 w l dt 2 t 'perch x', data u 1:6 w l dt 2 t 'perch y', data u 1:8 w l dt 3 lw 2 lc rgb 'black' t 'paws y'
set title 'bird angle theta_b (Fig 5-13)'
set ylabel 'deg'
plot data u 1:10 w l lw 2 t 'ours', '-' w p pt 1 ps 3 lw 2 t 'thesis'
0.88 24.5
1.1 -60
e
set title 'finger tip-node y displacement (Fig 5-14)'
set ylabel 'mm'
plot for [i=0:4] data u 1:(column(11+i)) w l lw 2 t 'finger '.word('A B C D E', i+1), '-' w p pt 1 ps 3 lw 2 t 'thesis E'
0.94 -70.3
e
set title 'largest von Mises stress in each finger (Fig 5-15)'
set ylabel 'MPa'
plot for [i=0:4] data u 1:(column(16+i)) w l lw 2 t 'finger '.word('A B C D E', i+1), '-' w p pt 1 ps 3 lw 2 t 'thesis'
0.97 2.85
e
unset multiplot
