#!/usr/bin/env bash
# A contact sheet of a rendered run: frames of its video at given times, each labelled with its time, tiled four
# across into one PNG (ffmpeg only). The sheet in docs/images is the README's main job:
#   (cd /tmp && giantbubble run) && bash scripts/contact-sheet.sh /tmp/out/render.mp4 docs/images/main_job_contact_sheet.png
# Usage: contact-sheet.sh VIDEO OUT.png [TIME ...]   (seconds; default: 12 times through the run, placed by the
# pinch-off and burst that its stats.csv, beside the video, records)
set -euo pipefail

if [[ $# -lt 2 ]]; then
  echo "usage: $0 VIDEO OUT.png [TIME ...]" >&2
  exit 2
fi
video=$1
out=$2
shift 2
times=("$@")
# The time of the first frame whose events hold $1 in the run's stats.csv (docs/formats.md), or nothing.
event_time() {
  awk -F, -v event="$1" 'NR > 1 && (" " $NF " ") ~ (" " event " ") { print $2; exit }' "$(dirname "$video")/stats.csv" \
    2>/dev/null || true
}
if [[ ${#times[@]} -eq 0 ]]; then
  # The main job: the dip at rest, the bag drawn out, the wands closing, then from the pinch-off the free bubble
  # flying and sinking, and its burst. Without a pinch-off and a burst on record: evenly through 7 s.
  pinch=$(event_time pinched_off)
  burst=$(event_time burst_started)
  if [[ -n $pinch && -n $burst ]]; then
    mapfile -t times < <(awk -v p="$pinch" -v b="$burst" 'BEGIN {
      split("0.4 1.0 1.4", early, " "); for (k = 1; k <= 3; ++k) if (early[k] < p - 0.1) printf "%.1f\n", early[k];
      printf "%.2f\n%.2f\n", p - 0.1, p + 0.05;
      for (k = 1; k <= 3; ++k) printf "%.1f\n", p + 0.4 + k * (b - p - 0.6) / 4;
      printf "%.2f\n%.2f\n%.2f\n%.2f\n", b - 0.1, b + 0.05, b + 0.1, b + 0.2 }')
  else
    times=(0.4 1.0 1.4 1.7 1.9 2.3 3.0 3.8 4.5 5.0 6.0 7.0)
  fi
fi
command -v ffmpeg >/dev/null || { echo "$0: ffmpeg is not installed (apt-get install ffmpeg)" >&2; exit 1; }
[[ -f $video ]] || { echo "$0: no video at $video" >&2; exit 1; }

columns=4
rows=$(((${#times[@]} + columns - 1) / columns))
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
font=$(fc-match -f '%{file}' DejaVuSans 2>/dev/null || true)
k=0
for t in "${times[@]}"; do
  # One frame at time t, scaled to 480 wide, its time written in its corner (when fontconfig finds a font;
  # without one the frames go unlabelled).
  label=""
  [[ -n $font ]] && label=",drawtext=fontfile=${font}:text='${t} s':x=8:y=8:fontsize=22:fontcolor=white:box=1:boxcolor=black@0.5:boxborderw=4"
  ffmpeg -loglevel error -y -ss "$t" -i "$video" -frames:v 1 -vf "scale=480:-2${label}" "$work/$(printf '%02d' "$k").png"
  k=$((k + 1))
done
ffmpeg -loglevel error -y -framerate 1 -i "$work/%02d.png" -vf "tile=${columns}x${rows}:padding=4:color=white" \
  -frames:v 1 "$out"
echo "contact sheet: $out (${#times[@]} frames of $video)"
