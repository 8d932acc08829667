#!/usr/bin/env bash
# docs/report.png, the README's picture of the design report: the top of report.html of
# wei2017's optimum, checked by FE and refined, as headless Chromium (Debian's `chromium`)
# shows it 1100 px wide.
set -euo pipefail
cd "$(dirname "$0")/.."
bin="${CARGO_TARGET_DIR:-target}/release/flexopt"
cargo build --release --quiet
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# the refinement may stop at its budget (exit 4): its files and the report are written
"$bin" run problems/wei2017.toml --refine fe --verify --report --quiet --out "$tmp/out" >/dev/null || [ $? -eq 4 ]
chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
  --disable-background-networking --disable-component-update --disable-sync --hide-scrollbars \
  --user-data-dir="$tmp/profile" --window-size=1100,2000 --screenshot="$PWD/docs/report.png" \
  "file://$tmp/out/report.html" 2>/dev/null
echo "wrote docs/report.png"
