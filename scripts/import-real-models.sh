#!/usr/bin/env bash
# import-real-models.sh RASTERCMP TABLE MODELS_ROOT OUT_DIR
# Imports every line of TABLE (scenes/models.tsv: name, model file under MODELS_ROOT, import
# options) into OUT_DIR/NAME.json with `rastercmp import`. OUT_DIR is rebuilt whole: written beside
# it and swapped in, so a failed import leaves the previous suite. Exit 1 naming what failed.
set -euo pipefail
rastercmp=$1 table=$2 models=$3 out=$4
if [[ ! -d $models ]]; then
  echo "import-real-models: $models is missing: the real-model suite needs Debian's assimp-testmodels (scripts/setup.sh installs it)" >&2
  exit 1
fi
next="$out.next.$$"
rm -rf "$next"
mkdir -p "$next"
trap 'rm -rf "$next"' EXIT
count=0
while IFS=$'\t' read -r name model options; do
  [[ -z $name || $name == \#* ]] && continue
  # shellcheck disable=SC2086 # the options column is words
  if ! "$rastercmp" import "$models/$model" --name "$name" --out "$next/$name.json" $options >/dev/null; then
    echo "import-real-models: $table: $name: rastercmp import $models/$model $options failed" >&2
    exit 1
  fi
  count=$((count + 1))
done <"$table"
rm -rf "$out"
mv "$next" "$out"
trap - EXIT
echo "import-real-models: $count scene(s) in $out"
