# Columns of `dimerlab sweep --tsv` (docs/FORMATS.md, "Sweep files"), named once for every script.
AR = 1; FREQ = 2; GAMMA = 3; TILT = 4; DIAMETER = 10; MODE = 12; BOUNCING = 13
DRIFT = 14; DRIFT_ERR = 15; SCALED = 16; SCALED_ERR = 17; SURVIVED = 18; IMPACT_TYPE = 24
is_drift(dummy) = strcol(MODE) eq "drift"
# mode -> code for maps: rest 0, drift 1, jump 2, flutter 3, irregular 4 (failed points: NaN)
mode_code(dummy) = strcol(MODE) eq "rest" ? 0 : strcol(MODE) eq "drift" ? 1 : \
                   strcol(MODE) eq "jump" ? 2 : strcol(MODE) eq "flutter" ? 3 : \
                   strcol(MODE) eq "irregular" ? 4 : NaN
set datafile separator "\t"
set datafile missing "nan"
set terminal pngcairo size 1000,620 font "DejaVu Sans,11"
set grid lc rgb "#dddddd"
