#!/usr/bin/env bash
# Regenerates results/prr3_frequency/sweeps/: the natural frequencies of paper 002's 3-PRR
# against the hinge stiffness and the drive stiffness (Fig. 5) and against the platform and
# link masses (the mass ratio of Fig. 4 is mp / mg), around the paper's example.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
results=${RESULTS:-results}
out=$results/prr3_frequency/sweeps
example="rb=30,l=20,k=34.53"
while read -r param from to; do
  ./target/release/flexopt sweep problems/prr3_frequency.toml --param "$param" \
    --from "$from" --to "$to" --steps 200 --around "$example" --out "$out"
done <<'RANGES'
k 5 100
k1 1e5 1e7
mp 4 400
mg 0.5 40
RANGES
# Fig. 4: the inertia ratio Ip / Ig = (mp rb^2 / 4) / (mg l^2 / 3) changed through the platform
# radius, as the paper changed it (its masses also scaled with rb and l, by rules it does not
# give); inertia_ratio and mass_ratio are recorded beside the frequencies
./target/release/flexopt sweep problems/prr3_frequency.toml --param rb --from 10 --to 60 \
  --steps 200 --around "$example" --outputs f1,f2,f3,inertia_ratio --out "$out/inertia_ratio"
./target/release/flexopt sweep problems/prr3_frequency.toml --param mp --from 4 --to 400 \
  --steps 200 --around "$example" --outputs f1,f2,f3,mass_ratio --out "$out/mass_ratio"
