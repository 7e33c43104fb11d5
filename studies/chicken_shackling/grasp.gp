# Step 3 picture: the half bird on its perch in the hand (Table 5-6 global frame, mm), drawn from the
# surfaces `chicken_shackling --grasp <case> <end>` writes (grasp-case-<n>-{start,end}-{bird,hand}.dat, in
# build/results/chicken_shackling/grasp-case-<n>/). Run from the project root:
#   gnuplot -e "data='build/results/chicken_shackling/grasp-case-4/grasp-case-4-start'; out='grasp.png'; label='...'" \
#     studies/chicken_shackling/grasp.gp
# Optional `azimuth` [deg]: 330 (default) looks from the hand's side; 160 from the symmetry plane,
# where the half bird's cut shows the leg going down through the shackle plate to the perch.
# The bird's shades (0.25..1) use the palette's skin half; the hand, drum, perch and shackle's
# shades are moved up by 1 into its blue-grey half. y (up) is drawn as gnuplot's z.
set palette defined (0 '#3b2a1c', 0.5 '#a8805a', 1 '#f3dcb4', 1.0001 '#1c2a3b', 1.5 '#5a7aa8', 2 '#c8d8f0')
set cbrange [0:2]
unset colorbox
set pm3d depthorder corners2color c1 border lc rgb '#40000000' lw 0.2
set terminal pngcairo size 1000,750 enhanced font 'sans,12' background rgb 'white'
set output out
set title label
set view equal xyz
if (!exists('azimuth')) azimuth = 330
set view 65, azimuth, 1.5
unset border
unset tics
unset key
splot data.'-bird.dat' using 1:3:2:4 with pm3d, data.'-hand.dat' using 1:3:2:($4+1) with pm3d
