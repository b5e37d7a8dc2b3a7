# The fraction of drops that end in each mode, per (Gamma, A_r) point of a basin sweep (rows of
# every seed, docs/paper/make_figures.sh): one row per point, for docs/paper/mode_map_basins.gp.
BEGIN { FS = "\t"; OFS = "\t"; split("rest drift jump flutter irregular", M, " ") }
/^#/ { next }
{
  cell = sprintf("%.3f\t%.2f", $3, $1)
  if (!(cell in n)) order[++cells] = cell
  n[cell]++; c[cell, $12]++
}
END {
  print "# gamma\tar\tdrops\trest\tdrift\tjump\tflutter\tirregular"
  for (i = 1; i <= cells; i++) {
    cell = order[i]; line = cell "\t" n[cell]
    for (k = 1; k <= 5; k++) line = line sprintf("\t%.4g", c[cell, M[k]] / n[cell])
    print line
  }
}
