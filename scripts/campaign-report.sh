#!/usr/bin/env bash
# Runs a campaign with gyro_campaign and writes its report: a template's text with the
# campaign's summary in place of {{SUMMARY}}, the plots beside it.
# Usage: scripts/campaign-report.sh CAMPAIGN.json TEMPLATE.md.in OUT.md IMG_DIR [gyro_campaign options]
#   e.g. scripts/campaign-report.sh campaigns/seeker_faults.json campaigns/seeker_faults.md.in \
#          docs/fault-campaign.md docs/img/fault-campaign -j 2
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 4 ] || { sed -n '2,6p' "$0" >&2; exit 2; }
campaign=$1 template=$2 doc=$3 img=$4
shift 4
scripts/setup.sh
cmake --preset host >/dev/null
cmake --build --preset host --target gyro_campaign -j2 >/dev/null
out=build/campaigns/$(basename "$campaign" .json)
build/host/apps/campaign/gyro_campaign run "$campaign" -o "$out" "$@"

# The summary inside the report: headings one level down, plots from IMG_DIR.
mkdir -p "$img"
cp "$out"/plots/*.png "$img"/
rel=$(realpath --relative-to="$(dirname "$doc")" "$img")
summary=$(sed -e 's/^#/##/' -e "s#](plots/#](${rel}/#g" -e "s#!\[plots/#![#g" "$out/summary.md")
tmp=$(mktemp "$(dirname "$doc")/.$(basename "$doc").XXXXXX")
awk -v summary="$summary" '$0 == "{{SUMMARY}}" { print summary; next } { print }' "$template" > "$tmp"
chmod 644 "$tmp"
mv "$tmp" "$doc"
echo "wrote $doc (campaign outputs in $out)"
