#!/bin/sh
# Drive the live (modal) Stylize operator in a real Blender window under Xvfb.
#   tests/blender/run_windowed.sh [BUILD_DIR]
# Prints "N passed, M failed"; exits non-zero on any failure, a crash or a hang.
# Screenshots go to BUILD_DIR/screenshots/: the sidebar panel (panel.png), the Gauss sphere overlay
# (sphere_overlay.png) and a pin handle being dragged (handle_drag.png).
set -u
HERE=$(cd "$(dirname "$0")" && pwd)
BUILD=$(cd "${1:-$HERE/../../build}" && pwd) || { echo "windowed: no build dir"; exit 2; }
RESULT="$BUILD/screenshots/windowed_result.txt"
mkdir -p "$BUILD/screenshots"
rm -f "$RESULT"
timeout 600 xvfb-run -a -s "-screen 0 1280x800x24" \
    blender --factory-startup --enable-event-simulate --python-exit-code 1 \
    -P "$HERE/windowed_driver.py" -- "$BUILD"
STATUS=$?
if [ ! -s "$RESULT" ]; then
    echo "windowed: FAIL (Blender exited with $STATUS before writing a result)"
    echo "0 passed, 1 failed"
    exit 1
fi
LINE=$(cat "$RESULT")
echo "windowed summary: $LINE"
case "$LINE" in
    *" 0 failed") [ "$STATUS" -eq 0 ] && exit 0 ;;
esac
exit 1
