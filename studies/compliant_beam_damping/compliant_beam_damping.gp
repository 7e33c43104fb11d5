# Figures of study compliant_beam_damping. Variables set by the study: results (data folder), figures
# (output folder), term (svg or pngcairo) and ext (file extension).
set terminal @term size 800,520 noenhanced font 'sans,12' background rgb 'white'
set datafile commentschars '#'
set grid

# Fig 2-14: Rayleigh damping ratio versus natural frequency (Eq 2-45), alpha and beta of Eq 2-46/2-47.
set output figures.'/fig-2-14.'.ext
set title 'Fig 2-14  Proportional damping: zeta = (alpha/omega + beta omega)/2, alpha = 8.38 1/s, beta = 0.00106 s'
set xlabel 'natural frequency omega (rad/s)'
set ylabel 'damping ratio zeta'
set yrange [0:0.5]
set xrange [0:252]
set arrow 1 from first 2*pi*10, graph 0 to first 2*pi*10, graph 1 nohead dt 2 lc rgb '#888888'
set arrow 2 from first 2*pi*20, graph 0 to first 2*pi*20, graph 1 nohead dt 2 lc rgb '#888888'
set label 1 '10 Hz' at 2*pi*10+2, 0.46
set label 2 '20 Hz' at 2*pi*20+2, 0.46
plot results.'/fig-2-14.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'mass proportional (alpha only)', \
     '' using 1:3 with lines lw 2 lc rgb '#d62728' title 'stiffness proportional (beta only)', \
     '' using 1:4 with lines lw 3 lc rgb '#000000' title 'Rayleigh (alpha and beta)'
unset arrow
unset label
set autoscale xy

# Fig 2-17: FE tip response (20 elements) at the initial-guess alpha and at the critical alphas.
set output figures.'/fig-2-17.'.ext
info = system('cat '.results.'/fig-2-17.txt')
set title "Fig 2-17  FE tip response under different alpha (20 beam elements)\n".info
set xlabel 'time (s)'
set ylabel 'tip deflection (mm, downward)'
set arrow 1 from first 0.2, graph 0 to first 0.2, graph 1 nohead dt 2 lc rgb '#888888'
set label 1 'load released' at first 0.21, graph 0.95
plot results.'/fig-2-17.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'initial guess alpha = 3 1/s', \
     '' using 1:3 with lines lw 2 lc rgb '#d62728' title 'alpha_cr from the automated search (0.1 % overshoot)', \
     '' using 1:4 with lines lw 2 dt 2 lc rgb '#000000' title 'alpha_cr = alpha_g / zeta (log decrement) = 2 omega_1'
unset arrow
unset label

# Fig 2-18: FE tip response with the identified alpha against the SDOF model of Table 2-7 (top), and
# the Table 2-7 model itself, damped and undamped, as fitted to the measurement (bottom).
set terminal @term size 900,900 noenhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-2-18.'.ext
set multiplot layout 2,1
info = system('cat '.results.'/fig-2-18.txt')
set title "Fig 2-18  Free vibration: FE beam vs the SDOF model of Table 2-7\n".info
set xlabel 'time (s)'
set ylabel 'tip deflection (mm, downward)'
set yrange [-120:150]
set key top right
# With --full the 100-element curve is the thesis's whole 4 s (fig-2-18-fe100-4s.dat), else the first 0.85 s.
full = system('test -f '.results.'/fig-2-18-fe100-4s.dat && echo 1 || echo 0') + 0
fe100 = full ? results.'/fig-2-18-fe100-4s.dat' : results.'/fig-2-18-fe100.dat'
fe100_title = full ? 'FE, 100 elements (Table 2-9), 4 s, its identified alpha' : 'FE, 100 elements (Table 2-9), first 0.85 s'
plot results.'/fig-2-18-fe.dat' using 1:2 with lines lw 1 lc rgb '#1f77b4' title 'FE, 20 elements, identified alpha', \
     fe100 using 1:2 with lines lw 2 lc rgb '#2ca02c' title fe100_title, \
     results.'/fig-2-18-fe.dat' using 1:3 with lines lw 1 dt 3 lc rgb '#ff7f0e' title 'FE, 20 elements, thesis alpha = 0.165', \
     results.'/fig-2-18-sdof-overlay.dat' using 1:2 with lines lw 1 dt 2 lc rgb '#d62728' title 'SDOF (zeta 0.0055, 16.33 rad/s) from the first FE peak'
set title 'Table 2-7 SDOF model of the measured tip response (release from rest at 55.5)'
set ylabel 'tip displacement (mm, presumably)'
set yrange [-60:80]
plot results.'/fig-2-18-sdof.dat' using 1:3 with lines lw 1 lc rgb '#aaaaaa' title 'undamped: 55.5 s / (s^2 + 266.7)', \
     '' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'damped: (55.5 s + 9.969) / (s^2 + 0.1796 s + 266.7)'
unset multiplot
set autoscale y

# Fig 2-19: deflected shapes of the 100-element beam (identified alpha) at t = 0, 0.1, ..., 0.8 s.
set terminal @term size 900,520 noenhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-2-19.'.ext
set title 'Fig 2-19  Snapshots of the compliant beam (100 elements): load on until 0.2 s, then free vibration'
set xlabel 'x (mm)'
set ylabel 'y (mm)'
set key outside right
set xrange [0:420]
plot results.'/fig-2-19.dat' using 1:2 with lines lw 1 dt 2 lc rgb '#888888' title 't = 0 s', \
     for [k=2:9] '' using (column(2*k-1)):(column(2*k)) with linespoints lw 2 pt 7 ps 0.3 \
     title sprintf('t = %.1f s', 0.1*(k-1))
set autoscale x
set key inside

# Fig D-2: free response for several damping ratios, and the log decrement on one of them.
set terminal @term size 900,800 noenhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-d-2.'.ext
unset title
set multiplot layout 2,1 title 'Fig D-2  Damping ratio effect on the free response (omega_n = 2 pi, x(0) = 1)'
unset title
set xlabel 'time (s)'
set ylabel 'x(t) / x(0)'
set key outside right
zetas = '0.05 0.1 0.2 0.4 0.6 1.0 2.0'
plot for [i=2:8] results.'/fig-d-2.dat' using 1:i with lines lw 2 title 'zeta = '.word(zetas, i-1)
demo = system('cat '.results.'/fig-d-2-demo.txt')
set title 'log decrement (Eq D-3), zeta 0.05 + offset 0.5: '.demo
set ylabel 'x(t)'
plot results.'/fig-d-2-demo.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'sampled response', \
     results.'/fig-d-2-peaks.dat' using 1:2 with points pt 7 ps 1 lc rgb '#d62728' title 'peaks (parabolic interpolation)'
unset multiplot

# Fig D-4: magnification factor versus frequency ratio, and the half-power bandwidth on an FFT.
set output figures.'/fig-d-4.'.ext
unset title
set multiplot layout 2,1 title 'Fig D-4  Damping ratio effect in the frequency domain (Eq D-18)'
set xlabel 'frequency ratio r = omega / omega_n'
unset title
set ylabel 'magnification factor D_s'
set yrange [0:10.5]
zetas = '0.05 0.1 0.2 0.3 0.5 0.7 1.0'
plot for [i=2:8] results.'/fig-d-4.dat' using 1:i with lines lw 2 title 'zeta = '.word(zetas, i-1)
set autoscale y
demo = system('cat '.results.'/fig-d-4-demo.txt')
set title 'half-power (Eq D-17) on an FFT, impulse response zeta 0.05: '.demo
set ylabel '|X| / peak'
set xrange [0.5:1.5]
plot results.'/fig-d-4-demo.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'FFT amplitude', \
     results.'/fig-d-4-points.dat' using 1:2 with points pt 7 ps 1.2 lc rgb '#d62728' title 'peak and half-power points', \
     1/sqrt(2) with lines dt 2 lc rgb '#888888' title 'peak / sqrt 2'
unset multiplot
