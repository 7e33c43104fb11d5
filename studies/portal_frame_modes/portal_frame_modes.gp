# Figures of study portal_frame_modes. Variables set by the study: results (data folder), figures
# (output folder), term (svg or pngcairo) and ext (file extension). The mode-shape pages (many 3D
# wireframes) are drawn as PNG only.
set datafile commentschars '#'
set datafile missing 'nan'
load results.'/labels.gp'

# --- Fig 2-10: frequencies of Table 2-5 ------------------------------------------------------------
set terminal @term size 1000,760 noenhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-2-10.'.ext
set multiplot layout 2,1 title 'Fig 2-10  Portal frame: natural frequencies, FE models vs experiment (Table 2-5)'
set grid
set key top left
set xrange [0.5:30.5]
set xtics 1,1,30
set ylabel 'frequency (Hz)'
plot results.'/table-2-5.dat' using 1:4 with linespoints lw 1 pt 6 ps 1.2 lc rgb '#1f77b4' title 'thesis, assembled (ANSYS SHELL93)', \
     '' using 1:5 with linespoints lw 1 pt 8 ps 1.2 lc rgb '#ff7f0e' title 'thesis, single part', \
     '' using 1:6 with points pt 5 ps 1.0 lc rgb '#000000' title 'experiment (Guo et al. 2009)', \
     '' using 1:2 with linespoints lw 2 pt 7 ps 0.7 lc rgb '#1f77b4' title 'ours, assembled (MITC4, reconstructed frame)', \
     '' using 1:3 with linespoints lw 2 pt 9 ps 0.7 lc rgb '#ff7f0e' title 'ours, single part'
set xlabel 'mode'
set ylabel 'ours / thesis - 1 (%)'
set key top right
plot results.'/table-2-5.dat' using 1:(100*($2/$4-1)) with linespoints lw 2 pt 7 lc rgb '#1f77b4' title 'assembled', \
     '' using 1:(100*($3/$5-1)) with linespoints lw 2 pt 9 lc rgb '#ff7f0e' title 'single part', \
     0 with lines lc rgb '#888888' notitle
unset multiplot
set autoscale
unset xlabel
set xtics autofreq

# --- Fig 2-12: the screws and our choice of the missing ones -------------------------------------------
set terminal @term size 1100,520 noenhanced font 'sans,12' background rgb 'white'
set output figures.'/fig-2-12.'.ext
set multiplot layout 1,2 title 'Fig 2-12  Screws (16, CP sets on 6 DOF) and the missing-screw cases (best of the screw search)'
set size ratio -1
set title 'elevation: plates, L brackets, screws (projected)'
set xlabel 'x (m)'
set ylabel 'z (m)'
set key outside bottom center
plot results.'/fig-2-12-outline.dat' using 1:2 with lines lw 2 lc rgb '#444444' title 'mid-surfaces', \
     results.'/fig-2-12-screws.dat' using 1:2 with points pt 7 ps 1.0 lc rgb '#1f77b4' title 'screws'
set title 'left bracket unfolded: column leg | beam leg'
set xlabel 'y across the width (m); beam leg shifted by W + 4 cm'
set ylabel 'distance from the corner (m)'
set xrange [-0.02:2*W+0.06]
set yrange [0:0.22]
isleft(name) = strstrt(name, 'L-') == 1
u(name, x, y) = strstrt(name, 'L-col') == 1 ? y : (strstrt(name, 'L-beam') == 1 ? y + W + 0.04 : 1/0)
dist(name, x, z) = strstrt(name, 'L-col') == 1 ? H - z : x
plot results.'/fig-2-12-screws.dat' using ($4 == 0 ? u(stringcolumn(5), $1, $3) : 1/0):(dist(stringcolumn(5), $1, $2)) with points pt 7 ps 2 lc rgb '#1f77b4' title 'kept', \
     '' using ($4 == 1 ? u(stringcolumn(5), $1, $3) : 1/0):(dist(stringcolumn(5), $1, $2)) with points pt 2 ps 3 lw 3 lc rgb '#d62728' title 'missing in both cases', \
     '' using ($4 == 2 ? u(stringcolumn(5), $1, $3) : 1/0):(dist(stringcolumn(5), $1, $2)) with points pt 1 ps 3 lw 3 lc rgb '#ff7f0e' title 'missing in the 2-screw case', \
     '' using (u(stringcolumn(5), $1, $3)):(dist(stringcolumn(5), $1, $2)):5 with labels offset 0,1.3 font 'sans,9' notitle
unset multiplot
unset title
set autoscale
set size noratio

if (ext ne 'png') exit

# --- mode shapes: 3D wireframes of the deformed mid-surfaces (PNG) ------------------------------------
reset
set datafile commentschars '#'
set view 78, 345, 1.9, 1.0
set view equal xyz
unset border
unset tics
unset key
set xyplane 0
set xrange [-0.1:1.56]
set yrange [-0.2:0.35]
set zrange [0:1.0]
set margins 0,0,0,0

# Fig 2-11: the first modes whose shape differs between single-part and assembled models.
set terminal pngcairo size 1600,760 noenhanced font 'sans,11' background rgb 'white'
set output figures.'/fig-2-11.png'
set multiplot layout 2, n11 title 'Fig 2-11  Mode shapes that change between the assembled (top) and single-part (bottom) models'
do for [i=1:n11] {
    set title value('t11a'.i)
    splot results.'/fig-2-11-'.i.'-assembled.dat' with lines lc rgb '#1f77b4'
}
do for [i=1:n11] {
    set title value('t11s'.i)
    splot results.'/fig-2-11-'.i.'-single.dat' with lines lc rgb '#ff7f0e'
}
unset multiplot

# Fig 2-13: modes 12, 20, 21 and 27 of the assembled, missing-1 and missing-2 models.
set terminal pngcairo size 1400,1700 noenhanced font 'sans,11' background rgb 'white'
set output figures.'/fig-2-13.png'
set multiplot layout 4,3 title 'Fig 2-13  Missing-screw effect on modes 12, 20, 21, 27: assembled | missing 1 | missing 2'
do for [k in '12 20 21 27'] {
    set title 'assembled, mode '.k.' ('.value('fa'.k).' Hz)'
    splot results.'/mode-assembled-'.k.'.dat' with lines lc rgb '#1f77b4'
    set title 'missing 1 screw, mode '.k.' ('.value('f1'.k).' Hz)'
    splot results.'/mode-missing_1_screw-'.k.'.dat' with lines lc rgb '#d62728'
    set title 'missing 2 screws, mode '.k.' ('.value('f2'.k).' Hz)'
    splot results.'/mode-missing_2_screws-'.k.'.dat' with lines lc rgb '#ff7f0e'
}
unset multiplot

# Appendix C, Figs C-2..C-7: modes 1-30, five per page.
do for [page=2:7] {
    set terminal pngcairo size 1400,2000 noenhanced font 'sans,11' background rgb 'white'
    set output figures.'/fig-c-'.page.'.png'
    first = 5*(page-2) + 1
    set multiplot layout 5,3 title sprintf('Fig C-%d  Modes %d-%d: assembled | missing 1 screw | missing 2 screws', page, first, first+4)
    do for [k=first:first+4] {
        kk = sprintf('%02d', k)
        set title sprintf('assembled, mode %d (%s Hz)', k, value('fa'.k))
        splot results.'/mode-assembled-'.kk.'.dat' with lines lc rgb '#1f77b4'
        set title sprintf('missing 1, mode %d (%s Hz)', k, value('f1'.k))
        splot results.'/mode-missing_1_screw-'.kk.'.dat' with lines lc rgb '#d62728'
        set title sprintf('missing 2, mode %d (%s Hz)', k, value('f2'.k))
        splot results.'/mode-missing_2_screws-'.kk.'.dat' with lines lc rgb '#ff7f0e'
    }
    unset multiplot
}
