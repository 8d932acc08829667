#!/usr/bin/env bash
# Regenerates results/ into a temporary folder and fails unless every committed file (the
# benchmarks' excepted: their timings vary) comes out byte-identical and none is missing;
# a finite-element check's verify.json is compared without its timings.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bash scripts/regenerate.sh "$tmp"
status=0
# verify.json records how long its check took ("seconds"): compared without those
strip_seconds() {
  python3 -c 'import json,sys
def drop(v):
    if isinstance(v, dict): return {k: drop(x) for k, x in v.items() if k != "seconds"}
    if isinstance(v, list): return [drop(x) for x in v]
    return v
print(json.dumps(drop(json.load(open(sys.argv[1]))), indent=1))' "$1"
}
while IFS= read -r f; do
  rel=${f#results/}
  if [[ "$f" == */verify.json ]]; then
    if ! cmp -s <(strip_seconds "$f") <(strip_seconds "$tmp/$rel"); then
      echo "differs or missing: $f"
      status=1
    fi
    continue
  fi
  if ! cmp -s "$f" "$tmp/$rel"; then
    echo "differs or missing: $f"
    status=1
  fi
done < <(git ls-files results | grep -v '^results/bench/')
if [ "$status" -eq 0 ]; then
  echo "results: every committed file regenerates byte-identical"
fi
exit "$status"
