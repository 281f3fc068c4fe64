#!/bin/sh
# Drive the live (modal) Stylize operator in a real Blender window under Xvfb, in ten parts
# (windowed_kit.py: the helpers they share):
#   windowed_driver.py       the basics (keys, clicks, shape keys, deleting things, files)
#   windowed_live_run.py     undo during runs, the gizmo and other clicks, several objects, messages,
#                            converging
#   windowed_run_endings.py  Esc during a big set-up, a scripted run's progress, undo steps given back
#                            after every way a run ends
#   windowed_interactive.py  the Gauss sphere overlay and editing on it, pin handles dragged live
#   windowed_panel.py        the sidebar redrawn by operators, labels that fit it, the sphere's highlight
#                            and axis labels, the gpu state after draw callbacks, sidebar screenshots
#   windowed_undo_save.py    undo, Del and saving in the middle of a run or a bake lose nothing
#   windowed_paint_strength.py  Weight Paint strokes during a run, picked up back in Object Mode;
#                            Weight Paint reached by Ctrl+Tab, the header's mode menu and Paint Region
#   windowed_self_intersections.py  Avoid Self-Intersections ticked in the panel: a live run and a
#                            handle drag that cross the mesh through itself without it, not with it
#   windowed_follow_edits.py Follow Edits on the 35K bunny: G in Edit Mode, the copy follows; Ctrl+Z, it goes back
#   windowed_quit.py         quitting during a run must not save undo steps 0 in the preferences
#   tests/blender/run_windowed.sh [BUILD_DIR]
# Prints each part's result and "windowed summary: N passed, M failed"; exits non-zero on any
# failure, a crash or a hang. Screenshots go to BUILD_DIR/screenshots/: the sidebar panel (sidebar_*.png,
# settling_tooltip.png, bake_start_*.png), the Gauss sphere overlay (sphere_overlay.png), a pin handle
# being dragged (handle_drag.png, its header: handle_drag_header.png), a live run holding vertices back
# (self_intersections.png), Weight Paint during a run (weight_paint_mid_run.png, sidebar_paint_region.png) and a
# copy following its source's edit and its undo (follow_edits_followed.png, follow_edits_undone.png).
set -u
HERE=$(cd "$(dirname "$0")" && pwd)
BUILD=$(cd "${1:-$HERE/../../build}" && pwd) || { echo "windowed: no build dir"; exit 2; }
SHOTS="$BUILD/screenshots"
XVFB="xvfb-run -a -s"
SCREEN="-screen 0 1280x800x24"
mkdir -p "$SHOTS"
PASSED=0
FAILED=0

count() {  # $1: a line "N passed, M failed"
    p=${1%% passed*}
    f=${1#*passed, }
    f=${f%% failed*}
    PASSED=$((PASSED + p))
    FAILED=$((FAILED + f))
}

driver() {  # $1: driver script, $2: its result file in $SHOTS
    rm -f "$SHOTS/$2"
    timeout 1000 $XVFB "$SCREEN" blender --factory-startup --enable-event-simulate --python-exit-code 1 \
        -P "$HERE/$1" -- "$BUILD"
    status=$?
    if [ ! -s "$SHOTS/$2" ]; then
        echo "windowed: FAIL ($1: Blender exited with $status before writing a result)"
        FAILED=$((FAILED + 1))
        return
    fi
    line=$(cat "$SHOTS/$2")
    echo "windowed $1: $line"
    count "$line"
    [ "$status" -eq 0 ] || FAILED=$((FAILED + 1))
}

driver windowed_driver.py windowed_result.txt
driver windowed_live_run.py windowed_live_run_result.txt
driver windowed_run_endings.py windowed_run_endings_result.txt
driver windowed_interactive.py windowed_interactive_result.txt
driver windowed_panel.py windowed_panel_result.txt
driver windowed_undo_save.py windowed_undo_save_result.txt
driver windowed_paint_strength.py windowed_paint_strength_result.txt
driver windowed_self_intersections.py windowed_self_intersections_result.txt
driver windowed_follow_edits.py windowed_follow_edits_result.txt
driver windowed_proxy_run.py windowed_proxy_run_result.txt

# Quitting: the preferences live in a folder of their own, never the user's.
CONFIG=$(mktemp -d)
BLENDER_USER_CONFIG=$CONFIG blender -b --factory-startup -P "$HERE/windowed_quit.py" -- "$BUILD" save \
    > /dev/null 2>&1
BLENDER_USER_CONFIG=$CONFIG timeout 300 $XVFB "$SCREEN" blender --enable-event-simulate \
    -P "$HERE/windowed_quit.py" -- "$BUILD" quit > /dev/null 2>&1
OUT=$(BLENDER_USER_CONFIG=$CONFIG blender -b -P "$HERE/windowed_quit.py" -- "$BUILD" check 2>&1)
rm -rf "$CONFIG"
echo "$OUT" | grep -E "^(PASS|FAIL):"
LINE=$(echo "$OUT" | sed -n 's/^quit: //p')
if [ -n "$LINE" ]; then
    echo "windowed windowed_quit.py: $LINE"
    count "$LINE"
else
    echo "windowed: FAIL (windowed_quit.py wrote no result)"
    FAILED=$((FAILED + 1))
fi

echo "windowed summary: $PASSED passed, $FAILED failed"
[ "$FAILED" -eq 0 ]
