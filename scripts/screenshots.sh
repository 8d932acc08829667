#!/usr/bin/env bash
# Regenerates the README's terminal screenshots under docs/screenshots/ (the plots it shows
# are results/ files, which scripts/regenerate.sh makes). Needs DejaVu Sans Mono
# (Debian: fonts-dejavu-core).
set -euo pipefail
cd "$(dirname "$0")/.."
font=${FONT:-/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf}
cargo build --release --quiet --examples
./target/release/flexopt eval problems/wei2017.toml --format table \
  --design l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4 \
  | ./target/release/examples/text_png "$font" docs/screenshots/eval_table.png
./target/release/flexopt run problems/wei2017.toml --quiet --out "$(mktemp -d)" \
  | sed '/^wrote /d' | ./target/release/examples/text_png "$font" docs/screenshots/run_summary.png
