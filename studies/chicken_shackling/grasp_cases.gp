# Step 3, the five cases of Table 5-4 side by side (Figs 5-10, 5-11, 5-13 of the thesis), from the
# records `chicken_shackling --grasp <case>` writes (grasp-case-<n>.dat: t, body x y z, perch x y,
# paw x y z, theta_b, tip dy A..E, von Mises A..E, fingers-on-bird force). `records` is a sprintf
# pattern with the case number twice. Run from the project root:
#   gnuplot -e "records='build/results/chicken_shackling/grasp-case-%d/grasp-case-%d.dat'; out='cases.png'" \
#     studies/chicken_shackling/grasp_cases.gp
# What the README's criteria measure is drawn: the body centre's distance from the perch top centre
# less its value at t = 0 (case-4-closest, RMS over 0-0.9 s), the body's height over the perch
# (cases-1-3-oscillate, peak-to-peak over 0.3-0.9 s), the fingers' force on the bird (cases-1-2-hit
# over 0-0.9 s; only-case-4-releases: zero over 1.09-1.1 s) and theta_b (Case 4: +24.5 deg at 0.88 s,
# -60 deg at 1.1 s in the thesis).
set terminal pngcairo size 1400,1000 enhanced font 'sans,11' background rgb 'white'
set output out
data(n) = sprintf(records, n, n)
rpm = '35 40 45 45/20/40 45/19/45'
label(n) = sprintf('case %d (%s rpm)', n, word(rpm, n))
set multiplot layout 2,2 title 'Table 5-4: the five drum-speed cases (our half model; shackling at 0.9 s)'
set key top left font ',9'
set grid
set xlabel 't [s]'
set arrow 1 from 0.9, graph 0 to 0.9, graph 1 nohead dt 2 lc rgb 'gray40'
set title 'distance body centre - perch top centre (Fig 5-11; the same at t = 0 in every case)'
set ylabel 'mm'
plot for [n=1:5] data(n) u 1:(sqrt(($2-$5)**2 + ($3-$6)**2)) w l lw (n == 4 ? 3 : 1.5) t label(n)
set title 'body centre height over the perch top (Fig 5-11)'
plot for [n=1:5] data(n) u 1:($3-$6) w l lw (n == 4 ? 3 : 1.5) t label(n)
set title 'bird angle theta_b (Fig 5-13)'
set ylabel 'deg'
plot for [n=1:5] data(n) u 1:10 w l lw (n == 4 ? 3 : 1.5) t label(n), '-' w p pt 1 ps 3 lw 2 lc rgb 'black' t 'thesis, case 4'
0.88 24.5
1.1 -60
e
set title 'fingers'' contact force on the bird (Fig 5-10: hit, grasp, release)'
set ylabel 'N'
plot for [n=1:5] data(n) u 1:21 w l lw (n == 4 ? 3 : 1.5) t label(n)
unset multiplot
