# Figures of study topology_cases. Variables set by the study: results (data folder), figures (output
# folder), term (svg or pngcairo) and ext (file extension).
# Density maps: one filled box per element at its centroid, grey scale (light grey = void 0, black = solid 1).
set datafile commentschars '#'
# Light grey for void elements of the domain, so that its outline (wing, shackle hole) stays visible.
set palette defined (0 '#ececec', 1 'black')
set cbrange [0:1]
set cblabel 'pseudo-density'

# Compliance history: iteration vs compliance (the thesis plots ANSYS's compliance; ours in N mm).
# (The volume fraction is not drawn: the OC update holds it at the target from the first iteration.)
history(file, ttl, out) = sprintf("set output '%s'; set title '%s'; plot '%s' using 1:($2*1e3) with linespoints lw 2 pt 7 ps 0.6 lc rgb '#1f77b4' title 'compliance'", out, ttl, file)

set terminal @term size 800,500 enhanced font 'sans,12' background rgb 'white'
set grid
set xlabel 'iteration'
set ylabel 'compliance (N mm)'
set logscale y
eval history(results.'/cantilever-history.dat', 'Fig 2-20  Compliance minimization of the short cantilever (75 x 50 quad8, 70 % removed)', figures.'/fig-2-20.'.ext)
eval history(results.'/wing-history.dat', 'Fig 2-23  Compliance minimization of the chicken-wing domain (75 % removed)', figures.'/fig-2-23.'.ext)
unset logscale y
unset grid

density(file, ttl, out) = sprintf("set output '%s'; set title '%s'; plot '%s' using 1:2:3:4:5 with boxxyerror fs solid 1.0 noborder lc palette notitle", out, ttl, file)
set size ratio -1
set xlabel 'x (mm)'
set ylabel 'y (mm)'
set terminal @term size 800,560 enhanced font 'sans,12' background rgb 'white'
density_mm(file, ttl, out) = sprintf("set output '%s'; set title '%s'; plot '%s' using ($1*1e3):($2*1e3):($3*1e3):($4*1e3):5 with boxxyerror fs solid 1.0 noborder lc palette notitle", out, ttl, file)
set xrange [0:150]
set yrange [0:100]
eval density_mm(results.'/cantilever-density.dat', 'Fig 2-21a  Short cantilever, 70 % removed (load at the middle of the right end)', figures.'/fig-2-21.'.ext)
set xrange [-32:32]
set yrange [0:98]
set terminal @term size 560,800 enhanced font 'sans,12' background rgb 'white'
eval density_mm(results.'/wing-density.dat', 'Fig 2-24  Chicken-wing ligaments (reconstructed domain, 75 % removed)', figures.'/fig-2-24.'.ext)

# Shackle body: the unfolded L plate (x < -80 mm is the side plate, folded along x = -80 mm).
set terminal @term size 520,820 enhanced font 'sans,11' background rgb 'white'
set xrange [-162:2]
set yrange [-2:302]
set xlabel 'unfolded X (mm): bottom plate -80..0, side plate -160..-80'
set ylabel 'Z (mm)'
set arrow 1 from -80,0 to -80,300 nohead dt 2 lc rgb '#1f77b4' front
do for [p in "70 80 90"] {
  eval density_mm(results.'/shackle-'.p.'-density.dat', 'Fig 5-5  Shackle body (half model), '.p.' % removed', figures.'/fig-5-5-'.p.'.'.ext)
  eval density_mm(results.'/shackle-'.p.'-projected-density.dat', 'Fig 5-5  Shackle body, '.p.' % removed, Heaviside projection', figures.'/fig-5-5-'.p.'-projected.'.ext)
}
unset arrow 1

set terminal @term size 460,800 enhanced font 'sans,11' background rgb 'white'
set xrange [0:50]
set yrange [0:100]
set xlabel 'X (mm)'
set ylabel 'Y (mm)'
do for [p in "85 90"] {
  eval density_mm(results.'/gripper-'.p.'-density.dat', 'Fig 5-6  Gripper, '.p.' % removed', figures.'/fig-5-6-'.p.'.'.ext)
  eval density_mm(results.'/gripper-'.p.'-projected-density.dat', 'Fig 5-6  Gripper, '.p.' % removed, Heaviside projection', figures.'/fig-5-6-'.p.'-projected.'.ext)
}
