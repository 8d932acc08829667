#!/usr/bin/env bash
# The 3D check's cost as a user sees it, side by side in one run (interleaved, so that the
# machine's load falls on all alike): `flexopt verify` of wei2017's optimum (both 2D
# idealizations, the modes and the 3D check) and the same without the 3D check
# (`--no-3d`), CalculiX (`ccx`) on the 3D deck that verify writes (`part3d.inp`: the 3D
# check's largest solve, the first in-plane mesh of the whole part in 4 graded layers, whose
# stiffnesses are 0.17 % off the converged ones where verify's 3D values are within 0.03 %),
# and `run --refine fe` (the study and its refinement against 3D). Whole-process times,
# median of N (default 5), in results/bench/verify_3d.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-5}
cargo build --release --quiet
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
flexopt=./target/release/flexopt
optimum=results/wei2017/optimum.json
$flexopt verify problems/wei2017.toml --optimum "$optimum" --out "$tmp/v" >/dev/null
mkdir -p "$tmp/ccx"
cp "$tmp/v/part3d.inp" "$tmp/ccx/part.inp"
timed() { # name, command...
  local name=$1
  shift
  /usr/bin/time -f "%e %M" -o "$tmp/t" "$@" >/dev/null 2>&1
  echo "$name $(cat "$tmp/t")" >>"$tmp/all"
}
for _ in $(seq "$n"); do
  timed verify_3d $flexopt verify problems/wei2017.toml --optimum "$optimum" --out "$tmp/a"
  timed verify_2d $flexopt verify problems/wei2017.toml --optimum "$optimum" --out "$tmp/b" --no-3d
  timed ccx_part3d sh -c "cd $tmp/ccx && ccx part"
  timed refine_3d $flexopt run problems/wei2017.toml --refine fe --quiet --out "$tmp/r"
done
median() { grep "^$1 " "$tmp/all" | awk '{print $2}' | sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
peak() { grep "^$1 " "$tmp/all" | awk '{if ($3 > m) m = $3} END {print int(m / 1024)}'; }
mkdir -p results/bench
{
  echo "# whole-process seconds, median of $n interleaved runs, and peak MB ($(nproc) cores)"
  for k in verify_3d verify_2d ccx_part3d refine_3d; do
    printf "%-11s %8s s  %6s MB\n" "$k" "$(median $k)" "$(peak $k)"
  done
  awk -v a="$(median ccx_part3d)" -v b="$(median verify_3d)" -v c="$(median verify_2d)" \
    'BEGIN { printf "ccx on part3d.inp / verify with 3D: %.1fx; verify with 3D / without: %.2fx\n", a / b, b / c }'
} >results/bench/verify_3d.txt
cat results/bench/verify_3d.txt
