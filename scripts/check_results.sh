#!/usr/bin/env bash
# Regenerates results/ into a temporary folder and fails unless every committed file (the
# benchmarks' excepted: their timings vary) comes out byte-identical and none is missing;
# the JSON files that record timings are compared without them.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bash scripts/regenerate.sh "$tmp"
status=0
# verify.json and refined.json record how long their checks took ("seconds"): JSON files
# are compared without those, and manifest.json without the sizes and hashes of those two
normalize() {
  python3 -c 'import json,os,sys
TIMED = {"verify.json", "refined.json"}
def drop(v):
    if isinstance(v, dict): return {k: drop(x) for k, x in v.items() if k != "seconds"}
    if isinstance(v, list): return [drop(x) for x in v]
    return v
v = drop(json.load(open(sys.argv[1])))
if os.path.basename(sys.argv[1]) == "manifest.json":
    for f in v["files"]:
        if f["name"] in TIMED:
            f.pop("bytes"); f.pop("fnv1a64")
print(json.dumps(v, indent=1))' "$1"
}
while IFS= read -r f; do
  rel=${f#results/}
  if [[ "$f" == *.json ]]; then
    if [ ! -f "$tmp/$rel" ] || ! cmp -s <(normalize "$f") <(normalize "$tmp/$rel"); then
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
