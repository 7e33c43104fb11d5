# Figures of study football_sweep. Variables set by the study: results (data folder), figures
# (output folder), term (svg or pngcairo) and ext.
# case-<n>.dat columns: 1 t, 2 football x (mm), 3 football u_y (mm), 4 football x - pallet x (mm),
# 5 football stress (0.1 ms maxima, MPa), 6 the same CFC 60, 7 finger stress (MPa),
# 8-12 tip u_y of fingers A..E (mm), 13-17 cumulative contact impulse of fingers A..E (N s).
set datafile commentschars '#'
set grid
cases = '1 2 3 4 5'
colour(i) = word('#1f77b4 #d62728 #2ca02c #ff7f0e #9467bd', i)
file(i) = results.'/case-'.i.'.dat'

set terminal @term size 900,560 enhanced font 'sans,12' background rgb 'white'

# Fig 4-3: Case 4 y-trajectory, with the text's statement about the experiment.
set output figures.'/fig-4-3.'.ext
set title 'Fig 4-3  Football centre y-displacement, Case 4 (operating condition)'
set xlabel 'time (s)'
set ylabel 'u_y (mm)'
set object 1 rect from 1.80, graph 0 to 1.85, graph 1 fc rgb '#dddddd' fs solid 0.5 noborder behind
set arrow 1 from 1.6, 19.4 to 2.05, 19.4 nohead dt 2 lw 2 lc rgb 'black'
set label 1 'experimental maximum about 19.4 mm (text: simulation 2 mm higher at 1.80-1.85 s)' at 1.0, 19.4 offset 0,1 font 'sans,10'
# The football falls once it has left the pallet (README "Status"): the plot shows the lift.
set xrange [0.9:2.05]; set yrange [-40:60]; set key left bottom font 'sans,10'
full = results.'/case-4-full.dat'
if (system('test -f '.full.' && echo 1') eq '1') {
  plot file(4) using 1:3 with lines lw 3 lc rgb colour(4) title 'simulation, Case 4 (switch at 1.19 s), judged run from 0.95 s', \
       full using 1:3 with lines lw 1 lc rgb 'black' title '--full: Case 4 from t = 0 to 3 s'
} else {
  plot file(4) using 1:3 with lines lw 2 lc rgb colour(4) title 'simulation, Case 4 (switch at 1.19 s)'
}
unset object 1; unset arrow 1; unset label 1; set autoscale y; set key default

# Fig 4-4: football - pallet relative x.
set output figures.'/fig-4-4.'.ext
set title 'Fig 4-4  Relative x-displacement, football centre - pallet centre'
set ylabel 'x_{football} - x_{pallet} (mm)'
plot for [i in cases] file(i) using 1:4 with lines lw (i eq '4' ? 3 : 1) lc rgb colour(int(i)) title 'Case '.i

# Figs 4-6, 4-7, 4-8: all cases.
set output figures.'/fig-4-6.'.ext
set title 'Fig 4-6  Football centre x, Cases 1-5'
set ylabel 'x (mm)'
plot for [i in cases] file(i) using 1:2 with lines lw 2 lc rgb colour(int(i)) title 'Case '.i
set output figures.'/fig-4-7.'.ext
set title 'Fig 4-7  Football centre y-displacement, Cases 1-5 (clipped: it falls after leaving the pallet)'
set ylabel 'u_y (mm)'
set yrange [-40:60]
plot for [i in cases] file(i) using 1:3 with lines lw 2 lc rgb colour(int(i)) title 'Case '.i
set autoscale y
set output figures.'/fig-4-8.'.ext
set title 'Fig 4-8  Maximum equivalent stress in the football (CFC 60; grey: Case 4 unfiltered)'
set ylabel 'von Mises (MPa)'
plot file(4) using 1:5 with lines lc rgb '#cccccc' title 'Case 4, 0.1 ms maxima', \
     for [i in cases] file(i) using 1:6 with lines lw 2 lc rgb colour(int(i)) title 'Case '.i

# Fig 4-10: contact per finger (Case 2): cumulative impulse of the football's contact force.
set output figures.'/fig-4-10.'.ext
set title 'Fig 4-10  Contact of each finger with the football, Case 2 (cumulative impulse)'
set ylabel 'impulse (N s)'
set key left top
plot for [k=1:5] file(2) using 1:(column(12+k)) with lines lw 2 lc rgb colour(k) title 'finger '.word('A B C D E', k)

# Fig 4-11: finger-tip y-response (Case 2).
set output figures.'/fig-4-11.'.ext
set title 'Fig 4-11  Finger-tip y-displacement, Case 2'
set ylabel 'tip u_y (mm)'
plot for [k=1:5] file(2) using 1:(column(7+k)) with lines lw 2 lc rgb colour(k) title 'finger '.word('A B C D E', k)
set key default

# 3D views (Figs 4-1, 4-5, 4-9): surface quads of fingers and football, pallet and drum outline.
# Drawn as PNG only (thousands of polygons per panel).
if (ext eq 'png') {
  set terminal pngcairo size 1500,820 enhanced font 'sans,10' background rgb 'white'
  snap(c, k) = results.'/snap-case-'.c.'-'.k.'.dat'
  unset grid; unset xlabel; unset ylabel
  set view 60, 30, 1.9
  set view equal xyz
  set xyplane 0
  set xrange [-200:420]; set yrange [-130:230]; set zrange [-30:160]
  unset xtics; unset ytics; unset ztics; unset border
  set pm3d depthorder border lc rgb '#404040' lw 0.3
  set style fill solid 0.9
  unset colorbox
  unset key
  # x along the conveyor, z (depth) towards the drum, y up: splot x, z, y.
  do for [c in '4 2'] {
    set output figures.'/fig-4-'.(c eq '4' ? '5' : '9').'.png'
    nsnap = int(system('ls '.results.'/snap-case-'.c.'-*.dat 2>/dev/null | wc -l'))
    set multiplot layout 2,4 title (c eq '4' ? 'Fig 4-5  Case 4 (operating condition)' : 'Fig 4-9  Case 2 (optimal)').'  (mm; football moving in -x, drum turning at 20 rpm)'
    do for [k=0:(nsnap < 8 ? nsnap : 8) - 1] {
      set title system(sprintf("sed -n 's/^# t = \\([0-9.]*\\) s.*/t = \\1 s/p' %s", snap(c, k)))
      splot snap(c, k) index 0 using 1:3:2 with polygons fc rgb '#e8b04a', \
            ''         index 1 using 1:3:2 with polygons fc rgb '#8c4a2f', \
            ''         index 2 using 1:3:2 with lines lw 2 lc rgb '#303030', \
            ''         index 3 using 1:3:2 with lines lw 1 lc rgb '#6080a0'
    }
    unset multiplot
  }
  set output figures.'/fig-4-1.png'
  set terminal pngcairo size 900,650 enhanced font 'sans,11' background rgb 'white'
  set title system(sprintf("sed -n 's/^# t = \\([0-9.]*\\) s.*/Fig 4-1  The half model at the start of the run, t = \\1 s (fingers A-E, football, pallet, drum)/p' %s", snap(4, 0)))
  splot snap(4, 0) index 0 using 1:3:2 with polygons fc rgb '#e8b04a', \
        ''         index 1 using 1:3:2 with polygons fc rgb '#8c4a2f', \
        ''         index 2 using 1:3:2 with lines lw 2 lc rgb '#303030', \
        ''         index 3 using 1:3:2 with lines lw 1 lc rgb '#6080a0'
}
