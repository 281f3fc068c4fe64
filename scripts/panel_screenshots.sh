#!/bin/sh
# Screenshots of the Gauss sidebar at Blender's default width and UI scale 1, for the docs:
# idle, during a live run, a Custom slot with 20 normals, the Bake panel. Runs the windowed
# panel checks (tests/blender/windowed_panel.py, Blender 3.4 under Xvfb, about a minute) and
# copies the sidebar screenshots they take into docs/screenshots/.
#   scripts/panel_screenshots.sh [BUILD_DIR]
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
REPO=$(dirname "$HERE")
BUILD=$(cd "${1:-$REPO/build}" && pwd)
SHOTS="$BUILD/screenshots"
mkdir -p "$SHOTS"
rm -f "$SHOTS"/sidebar_*.png "$SHOTS/windowed_panel_result.txt"
timeout 400 xvfb-run -a -s "-screen 0 1280x800x24" blender --factory-startup --enable-event-simulate \
    --python-exit-code 1 -P "$REPO/tests/blender/windowed_panel.py" -- "$BUILD" > "$SHOTS/windowed_panel.log" 2>&1 || true
echo "windowed_panel.py: $(cat "$SHOTS/windowed_panel_result.txt" 2>/dev/null || echo 'no result')"
for name in sidebar_idle sidebar_live_run sidebar_custom_normals sidebar_bake; do
    [ -s "$SHOTS/$name.png" ] || { echo "no $name.png (see $SHOTS/windowed_panel.log)"; exit 1; }
    cp "$SHOTS/$name.png" "$REPO/docs/screenshots/$name.png"
done
echo "copied 4 sidebar screenshots to docs/screenshots/"
