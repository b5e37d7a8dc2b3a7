# Basins over (Γ, A_r): the fraction of random drops per point that end in each mode (25 Hz, the
# paper's coefficients). Drawn from docs/paper/data/mode_map_basins_fractions.tsv.
load "docs/paper/columns.gp"
set terminal pngcairo size 1100,820 font "DejaVu Sans,11"
set output "docs/paper/mode_map_basins.png"
set multiplot layout 2,2 title "Fraction of 8 random drops per point ending in each mode (periods 100-300, 25 Hz)"
set xlabel "Γ"
set ylabel "A_r"
set xrange [0.375:1.225]
set yrange [1.875:8.125]
set cbrange [0:1]
set palette defined (0 "#ffffff", 0.5 "#6baed6", 1 "#08306b")
B = "docs/paper/data/mode_map_basins_fractions.tsv"
set title "drift"
plot B using 1:2:5 with image notitle
set title "jump"
plot B using 1:2:6 with image notitle
set title "rest"
plot B using 1:2:4 with image notitle
set title "irregular"
plot B using 1:2:8 with image notitle
unset multiplot
