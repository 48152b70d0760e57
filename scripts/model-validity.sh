#!/usr/bin/env bash
# Regenerates docs/model-validity.md and its plot docs/img/model_validity.png: the report's
# model, the corrected model and the component against the gimbal plant over gimbal cone
# 0-25 deg, body turn 0-2 rad/s and roll 0-20 rad/s (210 cases), the settling after a change of
# command over the acceptance envelope (60 cases, three shapes) and the steady residual with
# heavier gimbal rings (6 x 18 cases): about 10 s after the build.
# Usage: scripts/model-validity.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset host >/dev/null
cmake --build --preset host --target gyro_model_validity
data=$(mktemp)
trap 'rm -f "$data"' EXIT
build/host/tools/gyro_model_validity --markdown docs/model-validity.md --data "$data" >/dev/null
gnuplot -e "data='$data'; out='docs/img/model_validity.png'" scripts/model-validity.gp
cat >> docs/model-validity.md <<'MD'

## Plot

![Open-loop error and closed-loop residual against roll](img/model_validity.png)

Left: the worst gimbal-angle error over 1 s, open loop, at a body turn of 1 rad/s, for the
report's model and the corrected one. Right: the component's worst residual, from uncaging on
and in steady slews, at the same turn; the dashed line is the acceptance bound of 2e-4 rad.
MD
echo "wrote docs/model-validity.md, docs/img/model_validity.png"
