#!/usr/bin/env bash
# The README's command lines, run as a user would type them: every `surfgrow` line of its sh
# blocks, and every command of its "Every command" table with the placeholders filled in
# (CLOUD, OUT, SCENE), must exit 0. Run by ctest (README.CommandLines) on the built binary; a
# cross build names the emulator that runs it (qemu-aarch64).
#   readme_commands.sh SURFGROW README [EMULATOR...]
set -euo pipefail
surfgrow=$(realpath "$1")
readme=$(realpath "$2")
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
mkdir bin
if [[ $# -eq 0 ]]; then
    ln -s "$surfgrow" bin/surfgrow
else
    printf '#!/bin/sh\nexec %s %s "$@"\n' "$*" "$surfgrow" >bin/surfgrow
    chmod +x bin/surfgrow
fi
export PATH="$work/bin:$PATH"

# What the commands read: a scan folder of a built-in scene, clouds in metres (PLY, PCD) and in
# millimetres (XYZ), a robot.
surfgrow scan --scene pipes -o scan/ >/dev/null
surfgrow scan2cloud scan/ -o cloud.ply -q
surfgrow scan2cloud scan/ -o scan.pcd -q
cp scan.pcd far.pcd
surfgrow scan2cloud scan/ -o metres.xyz -q
awk '{ printf "%.4f %.4f %.4f\n", 1000 * $1, 1000 * $2, 1000 * $3 }' metres.xyz >scan.xyz
cat >robot.json <<'JSON'
{"format": "surfgrow-robot", "units": "mm",
 "links": [{"name": "tool", "type": "sphere", "centre": [0, 0, 1000], "radius": 50}]}
JSON

# The table first (its grow makes OUT for the commands after it), then the sh blocks in order.
table=$(grep -E '^\| `surfgrow ' "$readme" | sed -E 's/^\| `([^`]*)`.*/\1/' |
    sed -E 's#\bCLOUD\b#scan/cloud.ply#g; s#\bOUT\b#out/#g; s#\bSCENE\b#pipes#g')
blocks=$(awk '/^```sh$/ { on = 1; next } /^```/ { on = 0 } on && /^surfgrow / { print }' "$readme" |
    sed -E 's/[[:space:]]+#.*$//')
[[ $(wc -l <<<"$table") -ge 10 && $(wc -l <<<"$blocks") -ge 8 ]] ||
    { echo "readme_commands: found too few command lines in $readme" >&2; exit 1; }

failed=0
count=0
while IFS= read -r line; do
    count=$((count + 1))
    status=0
    eval "$line" >log 2>&1 || status=$?
    if [[ $status -ne 0 ]]; then
        echo "FAILED (exit $status): $line" >&2
        tail -n 5 log >&2
        failed=$((failed + 1))
    fi
done <<<"$table"$'\n'"$blocks"
echo "readme_commands: $((count - failed)) of $count README command lines ran"
[[ $failed -eq 0 ]]
