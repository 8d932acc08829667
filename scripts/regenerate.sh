#!/usr/bin/env bash
# Regenerates every committed file of results/ but the benchmarks': the study of each problem
# in problems/ (the flexure networks too: wei2017_network, paper 004's bridge, and the
# rhombus, guide, lever, Scott-Russell and bridge-lever, and wei2017_stroke, the bridge
# optimized at its working stroke; but the sweep-only wei2017_fig9;
# wei2017's optimum refined by FE too, in wei2017_refined/; ti_first_mode's refined by its
# own [refine] section), the finite-element checks of wei2017's optimum and printed design,
# of bridge_circular's and of every network's optimum, the hinges' accuracy table, the
# trade-off front of wei2017_dynamic, and the sweeps of the three sweep scripts. With a folder as argument it writes there instead
# of results/ (scripts/check_results.sh compares such a copy with the committed files).
set -euo pipefail
cd "$(dirname "$0")/.."
export RESULTS=${1:-results}
cargo build --release --quiet
for p in wei2017_dynamic bridge_stress bridge_circular prr3_frequency pss3_frequency ti_first_mode \
  wei2017_min_stress wei2017_network rhombus_network guide_network lever_network \
  scott_russell_network bridge_lever_network wei2017_stroke; do
  ./target/release/flexopt run "problems/$p.toml" --quiet --out "$RESULTS/$p" >/dev/null
done
# paper 004's problem as the README's main job runs it (so that running it leaves the
# checkout as it is), and its optimum refined against the finite elements of the part
./target/release/flexopt run problems/wei2017.toml --quiet --out "$RESULTS/wei2017" >/dev/null
./target/release/flexopt run problems/wei2017.toml --refine fe --quiet \
  --out "$RESULTS/wei2017_refined" >/dev/null
# the finite-element check of the optimum and of paper 004's printed design (Table 1)
./target/release/flexopt verify problems/wei2017.toml --optimum "$RESULTS/wei2017/optimum.json" \
  --out "$RESULTS/wei2017/verify" >/dev/null
./target/release/flexopt verify problems/wei2017.toml --out "$RESULTS/wei2017/verify_printed" \
  --design l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4 >/dev/null
./target/release/flexopt verify problems/bridge_circular.toml \
  --optimum "$RESULTS/bridge_circular/optimum.json" --out "$RESULTS/bridge_circular/verify" >/dev/null
# the networks' parts checked through their ports (the lever and the guide whole, the
# rhombus and wei2017's network on their halves)
for n in lever_network guide_network rhombus_network wei2017_network; do
  ./target/release/flexopt verify "problems/$n.toml" \
    --optimum "$RESULTS/$n/optimum.json" --out "$RESULTS/$n/verify" >/dev/null
done
# wei2017's network optimized at its working stroke: its part's (linear) check, and its
# curves over the stroke beside the linear model's
./target/release/flexopt verify problems/wei2017_stroke.toml \
  --optimum "$RESULTS/wei2017_stroke/optimum.json" --out "$RESULTS/wei2017_stroke/verify" >/dev/null
./target/release/flexopt stroke problems/wei2017_stroke.toml \
  --optimum "$RESULTS/wei2017_stroke/optimum.json" --out "$RESULTS/wei2017_stroke/stroke" >/dev/null
# the Scott-Russell mechanism's part (its guided form) checked whole
./target/release/flexopt verify problems/scott_russell_network.toml \
  --optimum "$RESULTS/scott_russell_network/optimum.json" --out "$RESULTS/scott_russell_network/verify" >/dev/null
# the two-stage amplifier's part (its frame closed by the half's image) checked on its half
./target/release/flexopt verify problems/bridge_lever_network.toml \
  --optimum "$RESULTS/bridge_lever_network/optimum.json" --out "$RESULTS/bridge_lever_network/verify" >/dev/null
# the accuracy table of the hinge kinds (results/hinges/)
cargo run --release --quiet --example hinge_accuracy >/dev/null
./target/release/flexopt pareto problems/wei2017_dynamic.toml --vary natural_frequency \
  --from 400 --to 2000 --steps 17 --out "$RESULTS/wei2017_dynamic" >/dev/null
for s in fig9 prr3_sweeps pss3_sweeps; do
  bash "scripts/$s.sh" >/dev/null
done
