#!/usr/bin/env bash
# model-zfight-share.sh [BUILD]: for each *zfight_d16 case of the real-model suite (scenes/models.tsv),
# the share of pixels whose owner differs from the same model imported with the framing camera in
# D32 (the same eye and target, near and far holding the bounding sphere), both rendered on the CPU
# (exact path). Needs build/app/rastercmp and oiiotool (openimageio-tools). Prints a markdown table.
set -euo pipefail
build=${1:-build}
rastercmp=$build/app/rastercmp
models=/usr/share/assimp/models
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "| case | near, far | owners differing from D32 framed |"
echo "|---|---|---|"
while IFS=$'\t' read -r name model options; do
  [[ $name == *zfight_d16 ]] || continue
  # shellcheck disable=SC2086
  "$rastercmp" import "$models/$model" --name "$name" --out "$work/zf.json" $options >/dev/null </dev/null
  "$rastercmp" import "$models/$model" --out "$work/framed.json" >/dev/null
  "$rastercmp" render "$work/zf.json" --out "$work/zf" >/dev/null
  "$rastercmp" render "$work/framed.json" --out "$work/framed" >/dev/null
  diff=$(oiiotool "$work/zf/owner.tif" "$work/framed/owner.tif" --diff --failthresh 0 --warnthresh 0 --hardfail 0 2>&1 ||
    true)
  share=$(sed -n 's/.*pixels (\([0-9.]*%\)) over.*/\1/p' <<<"$diff" | sed -n 1p)
  near_far=$(sed -n 's/.*near=\([^,]*\),far=\([^ ]*\).*/\1, \2/p' <<<"$options")
  echo "| \`$name\` | $near_far | ${share:-0%} |"
  rm -rf "$work/zf" "$work/framed"
done < <(grep -v '^#' scenes/models.tsv)
