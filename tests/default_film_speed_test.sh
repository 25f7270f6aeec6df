#!/bin/bash
# bench/default_film_speed.sh's table and summary, on a stand-in for giantbubble that prints the Table 1 line of a run
# with frames/s from a list, quiet and busy runs in turn: the real-time factors, the least and median of each
# condition and their verdicts against x2.00; then a binary that prints no such line, which must stop the script with
# an error naming it.
set -euo pipefail
script=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

cat >"$dir/giantbubble" <<'STANDIN'
#!/bin/bash
count="$(dirname "$0")/count"
n=$(cat "$count" 2>/dev/null || echo 0)
echo $((n + 1)) >"$count"
fps=(110.0 90.0 130.0 95.0 100.0 105.0) # quiet, busy, quiet, busy, quiet, busy
printf '\n%-12s %18s %18s %26s\n%-12s %18s %18s %26s\n' Example "Avg. Particle Size" "Avg. Triangle Size" \
  "Avg. Time (fps) (simulation)" default 11908 23706 "${fps[$n]}"
STANDIN
chmod +x "$dir/giantbubble"
out=$(bash "$script" 3 "$dir/giantbubble")
echo "$out"
expect() {
  grep -qxF -- "$1" <<<"$out" || {
    echo "FAIL: no line '$1'"
    exit 1
  }
}
expect "2    quiet         130.0         2.60"
expect "2    busy           95.0         1.90"
expect "quiet  least x2.00, median x2.20 (target x2.00: met)"
expect "busy   least x1.80, median x1.90 (target x2.00: missed)"

printf '#!/bin/bash\necho "giantbubble run: no film"\n' >"$dir/silent"
chmod +x "$dir/silent"
if err=$(bash "$script" 1 "$dir/silent" 2>&1); then
  echo "FAIL: a run without a frames/s line passed: $err"
  exit 1
fi
grep -q "printed no frames/s line" <<<"$err" || {
  echo "FAIL: the error does not name the missing line: $err"
  exit 1
}
echo "default_film_speed.sh: table, summary and a run without figures as expected"
