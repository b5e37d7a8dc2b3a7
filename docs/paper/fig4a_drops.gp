# Fig. 4a from random drops: every drift orbit that 8 random drops per point reach (points)
# beside the drift release's curve (line), and the fraction of drops that end in the drift
# mode, at 25, 50 and 75 Hz with the paper's fixed diameter.
load "docs/paper/columns.gp"
set terminal pngcairo size 1300,760 font "DejaVu Sans,11"
set output "docs/paper/fig4a_drops.png"
set multiplot layout 2,3 title "Drift orbits from a drift release and from 8 random drops per A_r (Γ = 0.9, d = 9.5 mm)"
set xrange [2:10]
drift(dummy) = is_drift(0) ? column(SCALED) : NaN
share(dummy) = is_drift(0) ? 1.0 / 8 : 0
do for [k=0:2] {
  set title sprintf("%d Hz", 25 * (k + 1))
  set xlabel "A_r"
  set ylabel "<u> f / g"
  set yrange [-0.02:0.08]
  set key top right
  plot "docs/paper/data/fig4a.tsv" every 3::k using AR:(drift(0)) with lines lw 2 lc rgb "#4575b4" title "drift release", \
       "docs/paper/data/fig4a_drops.tsv" every 3::k using AR:(drift(0)) with points pt 7 ps 0.6 lc rgb "#d73027" title "random drops"
}
do for [k=0:2] {
  set title sprintf("%d Hz: drops ending in drift", 25 * (k + 1))
  set ylabel "fraction of drops"
  set yrange [0:1.05]
  plot "docs/paper/data/fig4a_drops.tsv" every 3::k using AR:(share(0)) smooth frequency with boxes fs solid 0.6 lc rgb "#d73027" notitle
}
unset multiplot
