#!/usr/bin/env bash
# Fresh machine -> packages, build, and the tumbling-box example (monitors, fields, plot).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
build/bin/emcontact inputs/tumbling_box.xml --output out/tumbling_box --overwrite
/usr/bin/python3 tools/plot_monitors.py out/tumbling_box/monitors.csv --out out/tumbling_box/energies.png
echo "results in out/tumbling_box (monitors.csv, fields.xdmf for ParaView, energies.png)"
