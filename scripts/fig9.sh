#!/usr/bin/env bash
# Regenerates results/wei2017/fig9/: the amplification of the general bridge against each of
# the six configuration parameters around the base design of paper 004's Fig. 9.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
results=${RESULTS:-results}
out=$results/wei2017/fig9
while read -r param from to; do
  ./target/release/flexopt sweep problems/wei2017_fig9.toml --param "$param" \
    --from "$from" --to "$to" --steps 401 --outputs amplification --out "$out"
done <<'RANGES'
l2 0.5 10
delta2 -20 20
l3 2 40
delta3 -20 20
l4 0.5 10
delta4 -20 20
RANGES
