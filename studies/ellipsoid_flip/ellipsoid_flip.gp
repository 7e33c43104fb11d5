# Figures of study ellipsoid_flip. Variables set by the study: results (data folder), figures
# (output folder), term (svg or pngcairo) and ext.
# grasp-flip.dat columns: 1 t, 2-4 object centre x, y, z (mm), 5-7 object centre in the hand's frame
# (mm), 8-9 drum centre point x, y (mm), 10-14 tip u_y of fingers A..E (mm).
# finger-stress.dat: 1 t, 2-6 CFC 60 of the 0.1 ms von Mises maxima of fingers A..E (MPa).
set datafile commentschars '#'
set grid
colour(i) = word('#1f77b4 #d62728 #2ca02c #ff7f0e #9467bd', i)
rec = results.'/grasp-flip.dat'
sig = results.'/finger-stress.dat'
set terminal @term size 900,560 enhanced font 'sans,12' background rgb 'white'

# Fig 4-15: finger-tip y-response during the grasp.
set output figures.'/fig-4-15.'.ext
set title 'Fig 4-15  Finger-tip y-displacement during the grasp (thesis: A largest, about 34 mm at 1.5 s)'
set xlabel 'time (s)'; set ylabel 'tip u_y (mm)'
set xrange [1.0:2.0]
set arrow 1 from 1.5, graph 0 to 1.5, graph 1 nohead dt 2 lc rgb 'black'
set label 1 'drum stops (180 deg)' at 1.505, graph 0.95 font 'sans,10'
set object 1 circle at 1.5, 34 size 0.006 fc rgb 'black' fs solid
set label 2 'thesis: A about 34 mm' at 1.51, 34 offset 0,-0.8 font 'sans,10'
set key left top
plot for [k=1:5] rec using 1:(column(9+k)) with lines lw 2 lc rgb colour(k) title 'finger '.word('A B C D E', k)
unset arrow 1; unset label 1; unset label 2; unset object 1

# Fig 4-16b: the peak finger stress.
set output figures.'/fig-4-16.'.ext
set title 'Fig 4-16b  Largest von Mises stress in each finger (CFC 60; thesis: 0.69 MPa on A at 1.48 s)'
set ylabel 'von Mises (MPa)'
set object 1 circle at 1.48, 0.69 size 0.006 fc rgb 'black' fs solid
plot for [k=1:5] sig using 1:(column(1+k)) with lines lw 2 lc rgb colour(k) title 'finger '.word('A B C D E', k)
unset object 1
set autoscale x

# Fig 4-18: trajectories of the object's centre and the drum's centre (when --full ran the flip).
flip = system('awk ''!/^#/ && $1 > 2.001 {print 1; exit}'' '.rec)
set output figures.'/fig-4-18.'.ext
if (flip eq '1') {
  set title 'Fig 4-18  Flip: trajectories of the ellipsoid centre and the drum centre (x-y plane, 2-3 s)'
  set xlabel 'x (mm)'; set ylabel 'y (mm)'
  set size ratio -1
  plot rec using ($1 >= 2.0 ? $2 : 1/0):3 with lines lw 2 lc rgb '#8c4a2f' title 'ellipsoid centre', \
       rec using ($1 >= 2.0 ? $8 : 1/0):9 with lines lw 2 lc rgb '#1f77b4' title 'drum centre point (0, 50.8, 0) mm'
  set size noratio
} else {
  set title 'Fig 4-18  (the flip runs with --full only: not in this run)'
  unset xlabel; unset ylabel
  set xrange [0:1]; set yrange [0:1]
  set label 1 'the flip (restart from the grasp at 2 s) runs with --full only' at 0.1, 0.5
  plot 2 notitle
  unset label 1
}
set autoscale

# 3D views (Figs 4-13, 4-17): surface quads of fingers and object. PNG only.
if (ext eq 'png') {
  set terminal pngcairo size 1500,820 enhanced font 'sans,10' background rgb 'white'
  snap(k) = results.'/snap-'.k.'.dat'
  unset grid; unset xlabel; unset ylabel
  set view 60, 30, 1.6
  set view equal xyz
  set xyplane 0
  set xrange [-250:300]; set yrange [-250:250]; set zrange [-200:250]
  unset xtics; unset ytics; unset ztics; unset border
  set pm3d depthorder border lc rgb '#404040' lw 0.3
  set style fill solid 0.9
  unset colorbox; unset key
  nsnap = int(system('ls '.results.'/snap-*.dat 2>/dev/null | wc -l'))
  # splot x, z, y (y up).
  do for [fig in '13 17'] {
    first = (fig eq '13') ? 0 : 6
    last = (fig eq '13') ? (nsnap < 6 ? nsnap : 6) - 1 : nsnap - 1
    if (last >= first) {
      set output figures.'/fig-4-'.fig.'.png'
      set multiplot layout 2,3 title (fig eq '13' ? 'Fig 4-13  Grasp: the object carried to the drum centre, the hand turning to 180 deg at 1.5 s' : 'Fig 4-17  Flip: the hand turned 135 deg about z in 0.5 s, gravity on').'  (mm)'
      do for [k=first:last] {
        set title system(sprintf("sed -n 's/^# t = \\([0-9.]*\\) s.*/t = \\1 s/p' %s", snap(k)))
        splot snap(k) index 0 using 1:3:2 with polygons fc rgb '#e8b04a', \
              ''      index 1 using 1:3:2 with polygons fc rgb '#8c4a2f', \
              ''      index 2 using 1:3:2 with lines lw 3 lc rgb '#6080a0'
      }
      unset multiplot
    } else {
      set output figures.'/fig-4-'.fig.'.png'
      set terminal pngcairo size 600,200
      unset border
      set xrange [0:1]; set yrange [0:1]
      set label 1 'the flip runs with --full only' at 0.1, 0.5
      plot 2 notitle
      unset label 1
      set terminal pngcairo size 1500,820 enhanced font 'sans,10' background rgb 'white'
    }
  }
}
