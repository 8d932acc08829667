#!/usr/bin/env bash
# Regenerates results/ into a temporary folder and fails unless every committed file (the
# benchmarks' excepted: their timings vary) comes out byte-identical and none is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bash scripts/regenerate.sh "$tmp"
status=0
while IFS= read -r f; do
  rel=${f#results/}
  if ! cmp -s "$f" "$tmp/$rel"; then
    echo "differs or missing: $f"
    status=1
  fi
done < <(git ls-files results | grep -v '^results/bench/')
if [ "$status" -eq 0 ]; then
  echo "results: every committed file regenerates byte-identical"
fi
exit "$status"
