#!/usr/bin/env bash
# Regenerates results/pss3_frequency/sweeps/: the x (= y) natural frequency of paper 000's
# 3-PSS, with the rods' angle theta_l, around the paper's example (l = 65 mm, Er = 20 mm,
# kbm = 5.18 N m/rad, the problem file's masses):
#   kbm/                 Fig. 5: against the hinge stiffness, 1-10 N m/rad
#   mass_ratio/          Fig. 6: each component's mass from 1 to 2 times its value
#   added_mass/          Fig. 7: 0 to 2 g added to the platform, a slider or a rod
#   l.json, ra.json      Fig. 8: against l (65-100 mm) and Er = ra - 25 mm (20-60 mm)
#   theta_at_l65/70/75/  Fig. 9a: against ra at l = 65, 70, 75 mm (theta_l in the JSON)
#   theta_at_er20/40/60/ Fig. 9b: against l at Er = 20, 40, 60 mm
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
results=${RESULTS:-results}
out=$results/pss3_frequency/sweeps
problem=problems/pss3_frequency.toml
sweep() { # folder param from to around
  ./target/release/flexopt sweep "$problem" --param "$2" --from "$3" --to "$4" --steps 200 \
    --around "$5" --outputs f_x,theta_l --out "$out/$1"
}
example="ra=45,l=65,kbm=5.18"
sweep kbm kbm 1 10 "$example"
sweep mass_ratio mp 108.08 216.16 "$example"
sweep mass_ratio mb 24.08 48.16 "$example"
sweep mass_ratio mc 4 8 "$example"
sweep added_mass mp 108.08 110.08 "$example"
sweep added_mass mb 24.08 26.08 "$example"
sweep added_mass mc 4 6 "$example"
sweep . l 65 100 "$example"
sweep . ra 45 85 "$example"
for l in 65 70 75; do
  sweep "theta_at_l$l" ra 42 89 "ra=45,l=$l,kbm=5.18"
done
for er in 20 40 60; do
  sweep "theta_at_er$er" l "$((er + 5))" 100 "ra=$((25 + er)),l=100,kbm=5.18"
done
