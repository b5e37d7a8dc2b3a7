# <u> f/g against Γ at A_r 3.9, 25 Hz, from a drift release (the paper: nearly constant for
# Γ 0.5-1.1, rest below, jump and flutter above). Colour: the mode over the measured window.
load "docs/paper/columns.gp"
set output "docs/paper/gamma_curve.png"
set title "Drift speed against the drive, A_r = 3.9, 25 Hz, drift release"
set xlabel "Γ"
set ylabel "<u> f / g"
set xrange [0.25:1.35]
set key top left
m(code) = mode_code(0) == code ? column(SCALED) : NaN
plot "docs/paper/data/gamma_curve.tsv" using GAMMA:(m(1)):SCALED_ERR with yerrorbars pt 7 lc rgb "#4575b4" title "drift", \
     "" using GAMMA:(m(0)) with points pt 5 lc rgb "#888888" title "rest", \
     "" using GAMMA:(m(2)) with points pt 9 lc rgb "#d73027" title "jump", \
     "" using GAMMA:(m(3)) with points pt 11 lc rgb "#fdae61" title "flutter", \
     "" using GAMMA:(m(4)) with points pt 3 lc rgb "#000000" title "irregular"
