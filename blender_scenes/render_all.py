"""Build, stylize and render every demo scene into one folder (.blend + .png each).

    blender -b --factory-startup --python-exit-code 1 -P blender_scenes/render_all.py -- \
        BUILD_DIR OUT_DIR [--gallery DIR] [--only NAME[,NAME...]]

BUILD_DIR is a build tree with the staged add-on (scripts/build.sh), OUT_DIR receives
NAME.blend and NAME.png per scene, --gallery DIR additionally copies the PNGs there (the
README's docs/gallery/ was made this way). Test meshes from ../shared/meshes are used when
present, Blender primitives otherwise.
"""

import argparse
import os
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import default_scene  # noqa: E402
import render_kit  # noqa: E402
import scene_bake  # noqa: E402
import scene_cube_stays_cube  # noqa: E402
import scene_cubic_vs_gauss  # noqa: E402
import scene_extreme  # noqa: E402
import scene_from_example  # noqa: E402
import scene_gauss_map  # noqa: E402
import scene_gauss_sphere  # noqa: E402
import scene_handles  # noqa: E402
import scene_keep_volume  # noqa: E402
import scene_kit  # noqa: E402
import scene_multistyle  # noqa: E402
import scene_paint_strength  # noqa: E402
import scene_pins  # noqa: E402
import scene_self_intersections  # noqa: E402
import scene_sheet_metal  # noqa: E402
import scene_sigma  # noqa: E402
import scene_square_flat_regions  # noqa: E402
import scene_style_reach  # noqa: E402
import scene_styles  # noqa: E402

SCENES = (default_scene, scene_cube_stays_cube, scene_styles, scene_sigma, scene_pins,
          scene_multistyle, scene_extreme, scene_cubic_vs_gauss, scene_bake, scene_keep_volume, scene_handles,
          scene_from_example, scene_gauss_sphere, scene_paint_strength, scene_self_intersections,
          scene_sheet_metal, scene_style_reach, scene_square_flat_regions, scene_gauss_map)


def main():
    parser = argparse.ArgumentParser(prog="render_all.py")
    parser.add_argument("build_dir")
    parser.add_argument("out_dir")
    parser.add_argument("--gallery", help="also copy the PNGs into this folder")
    parser.add_argument("--only", help="comma-separated scene names (default: all)")
    args = parser.parse_args(render_kit.script_args())
    build_dir, out_dir = os.path.abspath(args.build_dir), os.path.abspath(args.out_dir)
    chosen = SCENES
    if args.only:
        wanted = args.only.split(",")
        unknown = set(wanted) - {scene.NAME for scene in SCENES}
        if unknown:
            raise SystemExit("unknown scene(s) %s; known: %s"
                             % (", ".join(sorted(unknown)), ", ".join(s.NAME for s in SCENES)))
        chosen = [scene for scene in SCENES if scene.NAME in wanted]
    print("test meshes: %s" % (scene_kit.MESH_DIR if os.path.isdir(scene_kit.MESH_DIR)
                               else "not found, using Blender primitives"))
    scene_kit.load_addon(build_dir)
    total = time.perf_counter()
    for scene in chosen:
        png = render_kit.render_scene(scene, out_dir)
        if args.gallery:
            os.makedirs(args.gallery, exist_ok=True)
            shutil.copy(png, os.path.join(args.gallery, scene.NAME + ".png"))
    print("== all %d scenes: %.1f s -> %s" % (len(chosen), time.perf_counter() - total, out_dir))


if __name__ == "__main__":
    main()
