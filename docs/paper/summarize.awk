# The numbers docs/PAPER.md quotes, from the sweep TSVs (columns: docs/paper/columns.gp).
# Usage: awk -f summarize.awk fig4a.tsv fig4a_similar.tsv fig4b.tsv gamma_curve.tsv mode_map_fine.tsv
BEGIN { FS = "\t" }
/^#/ { next }
function base(f) { sub(/.*\//, "", f); sub(/\.tsv$/, "", f); return f }
{
  file = base(FILENAME); ar = $1 + 0; f = $2 + 0; g = $3 + 0; tilt = $4 + 0
  mode = $12; bouncing = $13 + 0; u = $14 + 0; uerr = $15 + 0; s = $16 + 0; type = $24
  key = sprintf("%.2f", ar)
  if (file == "fig4a" || file == "fig4a_similar") {
    if (mode == "drift") { S[file, f, key] = s; drift[file, f]++ }
    else nodrift[file, f] = nodrift[file, f] " " key
    if (f == 25 && file == "fig4a") T[key] = mode == "drift" ? type : "(" mode ")"
    ars[key] = ar
  } else if (file == "fig4b") {
    lab = u * (bouncing == 1 ? 1 : -1)
    if (mode == "drift" && (u > 2 * uerr || u < -2 * uerr) && tilt != 0) {
      if (lab * tilt > 0) { up++; if (tilt * tilt > maxup[key] * maxup[key]) maxup[key] = tilt }
      else down++
    } else if (tilt != 0) none++
  } else if (file == "gamma_curve") {
    G[sprintf("%.2f", g)] = mode; GS[sprintf("%.2f", g)] = s
  } else if (file == "mode_map_fine") {
    count[mode]++; total++
  }
}
function sorted_keys(arr, out,   k, n, i, j, t) {
  n = 0; for (k in arr) out[++n] = k
  for (i = 2; i <= n; i++) { t = out[i]; for (j = i - 1; j >= 1 && out[j] + 0 > t + 0; j--) out[j + 1] = out[j]; out[j + 1] = t }
  return n
}
END {
  n = sorted_keys(ars, K)
  for (fi = 1; fi <= 2; fi++) {
    file = fi == 1 ? "fig4a" : "fig4a_similar"
    printf "== %s: <u> f/g of a drift release against A_r (drift-mode points only)\n", file
    for (fq = 25; fq <= 75; fq += 25) {
      best = -1; bestk = ""; rev = ""; lo = ""; hi = ""
      for (i = 1; i <= n; i++) {
        k = K[i]; if (!((file, fq, k) in S)) continue
        if (lo == "") lo = k; hi = k
        if (S[file, fq, k] > best) { best = S[file, fq, k]; bestk = k }
        if (rev == "" && S[file, fq, k] < 0) rev = k
      }
      printf "  %d Hz: drift at %d of %d A_r values (%s..%s), peak %.4f at A_r %s, first backward at A_r %s; no drift at:%s\n", \
        fq, drift[file, fq], n, lo, hi, best, bestk, rev == "" ? "none" : rev, nodrift[file, fq]
    }
    # The frequency dependence: (u75 - u25)/u25 where both drift forward clearly (> 0.005).
    m = 0; sum = 0; mn = 1e9; mx = -1e9; maxabs = 0; ms = 0; ssum = 0; smn = 1e9; smx = -1e9
    for (i = 1; i <= n; i++) {
      k = K[i]
      if (!((file, 25, k) in S) || !((file, 75, k) in S)) continue
      d = S[file, 75, k] - S[file, 25, k]; ad = d < 0 ? -d : d; if (ad > maxabs) maxabs = ad
      if (S[file, 25, k] <= 0.005) continue
      if (k + 0 >= 3.6 && k + 0 <= 5.6) { ms++; ssum += d / S[file, 25, k]; if (d / S[file, 25, k] < smn) smn = d / S[file, 25, k]; if (d / S[file, 25, k] > smx) smx = d / S[file, 25, k] }
      r = d / S[file, 25, k]; m++; sum += r; if (r < mn) mn = r; if (r > mx) mx = r
    }
    if (ms) printf "  75 Hz vs 25 Hz on the smooth forward branch A_r 3.6..5.6 (%d values): relative change mean %+.2f %%, from %+.2f %% to %+.2f %%\n", ms, 100 * ssum / ms, 100 * smn, 100 * smx
    if (m) printf "  75 Hz vs 25 Hz where both drift forward (%d A_r values): relative change mean %+.2f %%, from %+.2f %% to %+.2f %%; largest |difference| %.3g (in g/f)\n", m, 100 * sum / m, 100 * mn, 100 * mx, maxabs
  }
  print "== the bouncing end's most frequent impact outcome along A_r (fig4a, 25 Hz)"
  prev = ""; start = ""
  for (i = 1; i <= n; i++) {
    k = K[i]; t = T[k]
    if (t != prev) { if (prev != "") printf "  A_r %s..%s: %s\n", start, last, prev; prev = t; start = k }
    last = k
  }
  if (prev != "") printf "  A_r %s..%s: %s\n", start, last, prev
  print "== fig4b: drift direction on a tilted plate (tilt != 0 points)"
  printf "  uphill %d, downhill %d, no drift %d\n", up, down, none
  m = sorted_keys(maxup, U); line = ""
  for (i = 1; i <= m; i++) line = line sprintf(" %s:%+.2f", U[i], maxup[U[i]])
  print "  steepest uphill tilt (deg) per A_r:" line
  print "== gamma_curve: A_r 3.9, 25 Hz, drift release"
  m = sorted_keys(G, GG); line = ""
  for (i = 1; i <= m; i++) line = line sprintf(" %s:%s%s", GG[i], G[GG[i]], G[GG[i]] == "drift" ? sprintf("(%.4f)", GS[GG[i]]) : "")
  print " " line
  print "== mode_map_fine: modes from random drops"
  for (k in count) printf "  %s %d (%.1f %%)\n", k, count[k], 100 * count[k] / total
}
