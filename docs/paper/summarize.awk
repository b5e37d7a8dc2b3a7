# The numbers docs/PAPER.md quotes, from the sweep TSVs (columns: docs/paper/columns.gp); run by
# docs/paper/summarize.sh. Prints readable sections, then every quoted number as `name = value`
# (docs/paper/render_paper.sh puts them into docs/paper/PAPER.md.in).
BEGIN { FS = "\t"; nnum = 0 }
/^#/ { next }
function base(f) { sub(/.*\//, "", f); sub(/\.tsv$/, "", f); return f }
function num(name, value) { if (!(name in NUM)) ORDER[++nnum] = name; NUM[name] = value }
function k2(x) { return sprintf("%.2f", x) }
function abs(x) { return x < 0 ? -x : x }
{
  file = base(FILENAME)
  o = file == "releases" ? 1 : 0  # releases.tsv: the lift first, then a sweep row
  ar = $(1 + o) + 0; f = $(2 + o) + 0; g = $(3 + o) + 0; tilt = $(4 + o) + 0
  mode = $(12 + o); bouncing = $(13 + o) + 0; u = $(14 + o) + 0; uerr = $(15 + o) + 0
  s = $(16 + o) + 0; type = $(24 + o); frac = $(25 + o) + 0
  key = k2(ar)
  if (file == "fig4a" || file == "fig4a_similar") {
    if (mode == "drift") { S[file, f, key] = s; drift[file, f]++ }
    else nodrift[file, f] = nodrift[file, f] " " key
    TY[file, f, key] = mode == "drift" ? type : "(" mode ")"
    ars[key] = ar
  } else if (file == "fig4b") {
    lab = u * (bouncing == 1 ? 1 : -1)
    if (mode == "drift" && abs(u) > 2 * uerr && tilt != 0) {
      if (lab * tilt > 0) { up++; if (abs(tilt) > abs(maxup[key])) maxup[key] = tilt }
      else down++
    } else if (tilt != 0) none++
    if (tilt != 0) tilted++
  } else if (file == "gamma_curve") {
    G[k2(g)] = mode; GS[k2(g)] = s; GT[k2(g)] = type; GF[k2(g)] = frac
  } else if (file == "mode_map_fine") {
    count[mode]++; total++
    if (g < 0.65 && mode != "rest") low_g_not_rest++
    if (ar < 2.8 && mode == "drift") short_drift++
    if (g > 1) { above1++; above1_mode[mode]++; if (ar >= 3) { above1_long++; above1_long_mode[mode]++ } }
  } else if (file == "fig4a_drops") {
    cell = f SUBSEP key
    dn[cell]++; if (mode == "drift") { dd[cell]++; DS[cell, dd[cell]] = s }
    dars[key] = ar
  } else if (file == "mode_map_basins") {
    cell = k2(g) SUBSEP key
    bn[cell]++; bm[cell, mode]++
    if (!((cell, mode) in seen)) { seen[cell, mode] = 1; bkinds[cell]++ }
  } else if (file == "releases") {
    R[f, key, $1] = mode == "drift" ? sprintf("%.4f", s) : mode
    rlifts[$1] = $1 + 0
  }
}
function sorted_keys(arr, out,   k, n, i, j, t) {
  n = 0; for (k in arr) out[++n] = k
  for (i = 2; i <= n; i++) { t = out[i]; for (j = i - 1; j >= 1 && out[j] + 0 > t + 0; j--) out[j + 1] = out[j]; out[j + 1] = t }
  return n
}
# Fig. 4a per file and frequency: where the release drifts, its peak, the reversal.
function fig4a(file, fq,   i, k, best, bestk, rev, lo, hi, lastf, lastfs, p, zero) {
  best = -1; rev = ""; lo = ""; lastf = ""
  for (i = 1; i <= n; i++) {
    k = K[i]; if (!((file, fq, k) in S)) continue
    if (lo == "") lo = k; hi = k
    if (S[file, fq, k] > best) { best = S[file, fq, k]; bestk = k }
    if (rev == "" && S[file, fq, k] < 0) rev = k
    if (rev == "" && S[file, fq, k] > 0) { lastf = k; lastfs = S[file, fq, k] }
  }
  p = file "." fq "hz."
  printf "  %d Hz: drift at %d of %d A_r values (%s..%s), peak %.4f at A_r %s, first backward at A_r %s; no drift at:%s\n", \
    fq, drift[file, fq], n, lo, hi, best, bestk, rev == "" ? "none" : rev, nodrift[file, fq]
  num(p "drift_count", drift[file, fq]); num(p "count", n); num(p "drift_lo", lo + 0)
  num(p "peak", sprintf("%.4f", best)); num(p "peak_ar", bestk + 0)
  num(p "last_forward_ar", lastf + 0); num(p "last_forward", sprintf("%+.4f", lastfs))
  if (rev == "") return
  num(p "first_backward_ar", rev + 0); num(p "first_backward", sprintf("%+.4f", S[file, fq, rev]))
  # The backward branch ends where the speed first comes within 0.001 of zero (or turns).
  zero = ""
  for (i = 1; i <= n; i++) {
    k = K[i]; if (k + 0 <= rev + 0 || !((file, fq, k) in S)) continue
    if (zero == "" && S[file, fq, k] > -0.001) zero = k
  }
  num(p "backward_end_ar", zero == "" ? "none" : zero + 0)
  if (zero != "") num(p "at_backward_end", sprintf("%+.5f", S[file, fq, zero]))
  num(p "at_ar10", sprintf("%+.5f", S[file, fq, K[n]]))
}
# Ranges of equal impact type along A_r (the bouncing end's most frequent outcome).
function type_ranges(file, fq, name,   i, k, t, prev, start, last, line) {
  prev = ""; line = ""
  for (i = 1; i <= n; i++) {
    k = K[i]; t = TY[file, fq, k]
    if (t != prev) { if (prev != "") line = line sprintf("%s%s–%s %s", line == "" ? "" : "; ", start + 0, last + 0, prev); prev = t; start = k }
    last = k
  }
  line = line sprintf("%s%s–%s %s", line == "" ? "" : "; ", start + 0, last + 0, prev)
  printf "  %d Hz: %s\n", fq, line
  num(name, line)
}
END {
  n = sorted_keys(ars, K)
  for (fi = 1; fi <= 2; fi++) {
    file = fi == 1 ? "fig4a" : "fig4a_similar"
    printf "== %s: <u> f/g of a drift release against A_r (drift-mode points only)\n", file
    for (fq = 25; fq <= 75; fq += 25) fig4a(file, fq)
    # The frequency dependence: (u75 - u25)/u25 where both drift forward clearly (> 0.005).
    m = 0; sum = 0; mn = 1e9; mx = -1e9; maxabs = 0; ms = 0; ssum = 0; smn = 1e9; smx = -1e9
    for (i = 1; i <= n; i++) {
      k = K[i]
      if (!((file, 25, k) in S) || !((file, 75, k) in S)) continue
      d = S[file, 75, k] - S[file, 25, k]; if (abs(d) > maxabs) maxabs = abs(d)
      if (S[file, 25, k] <= 0.005) continue
      r = d / S[file, 25, k]
      if (k + 0 >= 3.6 && k + 0 <= 5.6) { ms++; ssum += r; if (r < smn) smn = r; if (r > smx) smx = r }
      m++; sum += r; if (r < mn) mn = r; if (r > mx) mx = r
    }
    p = file ".75vs25."
    if (ms) {
      printf "  75 Hz vs 25 Hz on the smooth forward branch A_r 3.6..5.6 (%d values): relative change mean %+.2f %%, from %+.2f %% to %+.2f %%\n", ms, 100 * ssum / ms, 100 * smn, 100 * smx
      num(p "smooth_mean_pct", sprintf("%+.1f", 100 * ssum / ms)); num(p "smooth_min_pct", sprintf("%+.1f", 100 * smn)); num(p "smooth_max_pct", sprintf("%+.1f", 100 * smx))
    }
    if (m) {
      printf "  75 Hz vs 25 Hz where both drift forward (%d A_r values): relative change mean %+.2f %%, from %+.2f %% to %+.2f %%; largest |difference| %.3g (in g/f)\n", m, 100 * sum / m, 100 * mn, 100 * mx, maxabs
      num(p "forward_min_pct", sprintf("%+.1f", 100 * mn)); num(p "forward_max_pct", sprintf("%+.1f", 100 * mx))
      num(p "largest_difference", sprintf("%.3g", maxabs))
    }
  }
  print "== the bouncing end's most frequent impact outcome along A_r (fig4a)"
  for (fq = 25; fq <= 75; fq += 25) type_ranges("fig4a", fq, "fig4a." fq "hz.impact_types")

  print "== fig4b: drift direction on a tilted plate (tilt != 0 points)"
  printf "  uphill %d, downhill %d, no drift %d\n", up, down, none
  num("fig4b.uphill", up + 0); num("fig4b.downhill", down + 0); num("fig4b.no_drift", none + 0); num("fig4b.tilted", tilted + 0)
  m = sorted_keys(maxup, U); line = ""; steepest = 0
  for (i = 1; i <= m; i++) {
    line = line sprintf(" %s:%+.1f", U[i] + 0, maxup[U[i]])
    if (abs(maxup[U[i]]) > abs(steepest)) { steepest = maxup[U[i]]; steepest_ar = U[i] + 0 }
  }
  print "  steepest uphill tilt (deg) per A_r:" line
  num("fig4b.steepest_per_ar", substr(line, 2)); num("fig4b.steepest", sprintf("%+.1f", steepest)); num("fig4b.steepest_ar", steepest_ar)

  print "== gamma_curve: A_r 3.9, 25 Hz, drift release"
  m = sorted_keys(G, GG); line = ""; lo = ""; first_type = ""; type_change = ""
  for (i = 1; i <= m; i++) {
    gk = GG[i]
    line = line sprintf(" %s:%s%s", gk, G[gk], G[gk] == "drift" ? sprintf("(%.4f)", GS[gk]) : "")
    if (G[gk] != "drift") { if (lo != "" && hi_done == "") hi_done = GG[i - 1]; continue }
    if (lo == "") { lo = gk; first_type = GT[gk]; smax = GS[gk]; smax_g = gk; smin = GS[gk] }
    if (GS[gk] > smax) { smax = GS[gk]; smax_g = gk }
    if (type_change == "" && GT[gk] != first_type) { type_change = gk; before = GS[GG[i - 1]]; after = GS[gk] }
    last = gk
  }
  print " " line
  num("gamma.drift_lo", lo + 0); num("gamma.drift_hi", last + 0)
  num("gamma.first_rest_below", GG[1] + 0)
  num("gamma.at_lo", sprintf("%.4f", GS[lo])); num("gamma.peak", sprintf("%.4f", smax)); num("gamma.peak_gamma", smax_g + 0)
  num("gamma.at_hi", sprintf("%.4f", GS[last]))
  num("gamma.first_type", first_type); num("gamma.type_change", type_change == "" ? "none" : type_change + 0)
  if (type_change != "") { num("gamma.before_change", sprintf("%.4f", before)); num("gamma.after_change", sprintf("%.4f", after)); num("gamma.second_type", GT[type_change]) }
  num("gamma.above_hi_mode", G[GG[m]])

  print "== mode_map_fine: modes from random drops (one drop per point)"
  split("rest drift jump flutter irregular", MODES, " ")
  for (i = 1; i <= 5; i++) {
    c = count[MODES[i]] + 0
    printf "  %s %d (%.1f %%)\n", MODES[i], c, 100 * c / total
    num("map." MODES[i], c); num("map." MODES[i] "_pct", sprintf("%.1f", 100 * c / total))
  }
  num("map.points", total); num("map.low_gamma_not_rest", low_g_not_rest + 0); num("map.short_drift", short_drift + 0)
  # Above Gamma 1: the share of each outcome, over all A_r and over A_r >= 3.
  num("map.above1.points", above1 + 0)
  num("map.above1.irregular_pct", sprintf("%.0f", 100 * above1_mode["irregular"] / above1))
  num("map.above1.drift_pct", sprintf("%.0f", 100 * above1_mode["drift"] / above1))
  num("map.above1.ar3.irregular_pct", sprintf("%.0f", 100 * above1_long_mode["irregular"] / above1_long))
  num("map.above1.ar3.drift_pct", sprintf("%.0f", 100 * above1_long_mode["drift"] / above1_long))

  print "== fig4a_drops: drift orbits from random drops (seeds per point, fraction ending in drift)"
  m = sorted_keys(dars, DK)
  for (fq = 25; fq <= 75; fq += 25) {
    reached = 0; lo = ""; two = ""
    for (i = 1; i <= m; i++) {
      cell = fq SUBSEP DK[i]
      if (!(cell in dd)) continue
      reached++; if (lo == "") lo = DK[i]
      # Two orbits: drift speeds of drops at one point that differ by more than 10 %.
      mn = 1e9; mx = -1e9
      for (j = 1; j <= dd[cell]; j++) { v = DS[cell, j]; if (v < mn) mn = v; if (v > mx) mx = v }
      if (mx - mn > 0.1 * abs(mx) && mx - mn > 0.002) two = two sprintf(" %s", DK[i] + 0)
    }
    seeds = dn[fq SUBSEP DK[1]]
    printf "  %d Hz: %d drops per point; drift reached at %d of %d A_r values (from A_r %s); two drift speeds at:%s\n", fq, seeds, reached, m, lo, two == "" ? " none" : two
    num("drops." fq "hz.reached", reached); num("drops." fq "hz.lo", lo + 0); num("drops." fq "hz.two_orbits", two == "" ? "none" : substr(two, 2))
    num("drops.seeds", seeds)
  }

  print "== mode_map_basins: basins over (Gamma, A_r) from several drops per point"
  cells = 0; multi = 0; drift_any = 0; drift_all = 0; maxk = 0
  for (cell in bn) {
    cells++; if (bkinds[cell] > 1) multi++
    if ((cell, "drift") in bm) drift_any++
    if (bm[cell, "drift"] == bn[cell]) drift_all++
    if (bkinds[cell] > maxk) maxk = bkinds[cell]
    if (bn[cell] > seeds_b) seeds_b = bn[cell]
  }
  printf "  %d points, %d drops each: %d reach more than one mode (up to %d); drift reached from %d, from every drop at %d\n", cells, seeds_b, multi, maxk, drift_any, drift_all
  num("basins.points", cells); num("basins.seeds", seeds_b); num("basins.multistable", multi)
  num("basins.most_modes", maxk); num("basins.drift_any", drift_any); num("basins.drift_all", drift_all)

  print "== releases: <u> f/g of a drift release by lift (fraction of d), or the mode reached"
  ml = sorted_keys(rlifts, L)
  split("3.20 3.30 5.70 5.80 5.90", RA, " ")
  for (fq = 25; fq <= 75; fq += 50) for (a = 1; a <= 5; a++) {
    line = ""
    for (i = 1; i <= ml; i++) line = line sprintf("%slift %s: %s", i > 1 ? ", " : "", L[i], R[fq, RA[a], L[i]])
    printf "  A_r %s, %d Hz: %s\n", RA[a] + 0, fq, line
    num("release." fq "hz.ar" RA[a] + 0, line)
  }

  print "== numbers (name = value): what docs/PAPER.md quotes"
  for (i = 1; i <= nnum; i++) printf "%s = %s\n", ORDER[i], NUM[ORDER[i]]
}
