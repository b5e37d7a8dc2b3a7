# The paper's Fig. 4b: the direction of the drift on a tilted plate over (A_r, tilt), 25 Hz.
# The lab velocity is the drift speed (positive toward the bouncing end) signed by the bouncing
# end's side; it is uphill when it has the sign of the tilt (tilt > 0 rises toward +x).
# "no drift": the dimer left the drift mode, or its speed is within 2 standard errors of 0.
load "docs/paper/columns.gp"
set output "docs/paper/fig4b.png"
lab(dummy) = column(DRIFT) * (column(BOUNCING) == 1 ? 1 : -1)
moving(dummy) = is_drift(0) && abs(column(DRIFT)) > 2 * column(DRIFT_ERR)
# 0 no drift, 1 uphill, 2 downhill, 3 drift on the level plate
class(dummy) = !moving(0) ? 0 : column(TILT) == 0 ? 3 : lab(0) * column(TILT) > 0 ? 1 : 2
colour(c) = c == 0 ? 0xbbbbbb : c == 1 ? 0x1a9850 : c == 2 ? 0xd73027 : 0x4575b4
set title "Drift direction on a tilted plate (25 Hz, Γ = 0.9, the paper's friction and restitution)"
set xlabel "A_r"
set ylabel "plate tilt (degrees, > 0 rising toward the bouncing end's side)"
set xrange [1.8:10.2]
set yrange [-8.3:8.3]
set key outside right top
plot "docs/paper/data/fig4b.tsv" using AR:TILT:(colour(class(0))) with points pt 5 ps 1.1 lc rgb variable notitle, \
     NaN with points pt 5 ps 1.1 lc rgb "#1a9850" title "uphill", \
     NaN with points pt 5 ps 1.1 lc rgb "#d73027" title "downhill", \
     NaN with points pt 5 ps 1.1 lc rgb "#4575b4" title "level plate", \
     NaN with points pt 5 ps 1.1 lc rgb "#bbbbbb" title "no drift"
