#!/usr/bin/env bash
# Takes the README's Blender add-on pictures (docs/images/blender-addon.png, the UI with the panel and the
# result; docs/images/blender-addon-render.png, the render) in Blender under Xvfb. Needs xvfb (not a
# test dependency: apt-get install xvfb).
#
#   scripts/blender-addon-screenshot.sh [BUILD_DIR]     (default build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tessera=${1:-$root/build}/bin/tessera
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# A user configuration without the splash screen, so that it does not cover the picture.
BLENDER_USER_CONFIG=$tmp/config blender -b --factory-startup \
  --python-expr "import bpy; bpy.context.preferences.view.show_splash = False; bpy.ops.wm.save_userpref()" >/dev/null
BLENDER_USER_CONFIG=$tmp/config timeout 300 xvfb-run -a -s "-screen 0 1800x1000x24" \
  blender --python "$root/scripts/blender_addon_screenshot.py" -- "$root" "$tessera" "$tmp" >/dev/null
oiiotool "$tmp/blender-addon.png" --resize 1440x800 -o "$root/docs/images/blender-addon.png"
cp "$tmp/blender-addon-render.png" "$root/docs/images/blender-addon-render.png"
echo "docs/images/blender-addon.png, docs/images/blender-addon-render.png" >&2
