#!/usr/bin/env bash
# The finite-element check at every corner of wei2017's bounds (2^8 designs: each length 0.5 or
# 20 mm, each angle -45 or 45 deg, each thickness 0.4 or 2 mm), each under a memory limit
# (ulimit -v, 8 GB) so that a check over its budget would be killed rather than swap: the
# exit code, the whole process's time and peak memory of each, and the largest of them, in
# results/bench/verify_corners.txt. Extra arguments go to every `verify` (e.g. --tolerance 0.1).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
out=results/bench/verify_corners.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
{
  echo "# flexopt verify at the corners of problems/wei2017.toml's bounds, extra arguments: ${*:-none}"
  echo "# exit  seconds  peak_MB  design"
} >"$tmp/table"
for l2 in 0.5 20; do for l3 in 0.5 20; do for l4 in 0.5 20; do
for d2 in -45 45; do for d3 in -45 45; do for d4 in -45 45; do
for t2 in 0.4 2; do for t4 in 0.4 2; do
  design="l2=$l2,delta2=$d2,t2=$t2,l3=$l3,delta3=$d3,l4=$l4,delta4=$d4,t4=$t4"
  set +e
  ( ulimit -v 8000000; /usr/bin/time -f "%e %M" -o "$tmp/time" ./target/release/flexopt verify \
      problems/wei2017.toml --design "$design" --out "$tmp/v" "$@" >/dev/null 2>"$tmp/err" )
  code=$?
  set -e
  read -r secs kb < <(tail -n 1 "$tmp/time") || { secs=nan; kb=0; }
  printf "%4s  %7s  %7d  %s\n" "$code" "$secs" "$((kb / 1024))" "$design" >>"$tmp/table"
done; done; done; done; done; done; done; done
awk '!/^#/ { n++; c[$1]++; if ($2 > t) t = $2; if ($3 > m) m = $3 }
     END { printf "# %d designs; exit codes:", n; for (k in c) printf " %s x%d", k, c[k];
           printf "; slowest %.2f s, largest %d MB\n", t, m }' "$tmp/table" >"$tmp/summary"
mkdir -p results/bench
cat "$tmp/summary" "$tmp/table" >"$out"
cat "$tmp/summary"
