# The mode reached from random drops over (Γ, A_r), 25 Hz, the paper's other parameters.
load "docs/paper/columns.gp"
set output "docs/paper/mode_map.png"
set title "Mode over periods 100-300 after a random drop (25 Hz, the paper's coefficients; one drop per point)"
set xlabel "Γ"
set ylabel "A_r"
# Five flat bands, one colour each (stops repeated so nothing is interpolated).
set palette defined (0 "#bbbbbb", 1 "#bbbbbb", 1 "#4575b4", 2 "#4575b4", 2 "#d73027", 3 "#d73027", \
                    3 "#fdae61", 4 "#fdae61", 4 "#000000", 5 "#000000")
set cbrange [-0.5:4.5]
set cbtics ("rest" 0, "drift" 1, "jump" 2, "flutter" 3, "irregular" 4)
set xrange [0.194:1.406]
set yrange [1.96:10.04]
plot "docs/paper/data/mode_map_fine.tsv" using GAMMA:AR:(mode_code(0)) with image notitle
