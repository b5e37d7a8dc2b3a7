# The paper's Fig. 4a: <u> f/g against A_r at 25, 50, 75 Hz; left at the paper's fixed diameter,
# right with the diameter scaled as 1/f^2 (dynamically similar). Only points that are in the
# drift mode over the measured window are drawn. Run from the repository root by
# docs/paper/make_figures.sh.
load "docs/paper/columns.gp"
set output "docs/paper/fig4a.png"
set multiplot layout 1,2 title "Drift speed against aspect ratio (Γ = 0.9, ε = 0.65, μ = 0.2, μ_s = 0.4; impacts: μ = 0.1, μ_s = 0.2)"
set xlabel "A_r"
set ylabel "<u> f / g"
set xrange [2:10]
set yrange [-0.02:0.08]
set key top right
set xzeroaxis lt -1
drift(dummy) = is_drift(0) ? column(SCALED) : NaN
# Rows run A_r slowest, then f (25, 50, 75): every 3rd row from row k is one frequency.
set title "fixed diameter d = 9.5 mm (the paper's)"
plot for [k=0:2] "docs/paper/data/fig4a.tsv" every 3::k \
       using AR:(drift(0)) with linespoints pt 7 ps 0.5 title sprintf("%d Hz", 25 * (k + 1))
set title "d = 9.5 mm x (25 Hz / f)^2 (lengths scale as gT^2)"
plot for [k=0:2] "docs/paper/data/fig4a_similar.tsv" every 3::k \
       using AR:(drift(0)) with linespoints pt 7 ps 0.5 title sprintf("%d Hz", 25 * (k + 1))
unset multiplot
