#!/usr/bin/env bash
# Renders the pictures the documentation shows (docs/images/) with the CLI
# that scripts/demo.sh builds, so that each picture is what quadra makes of
# its scene today, and writes docs/gallery.md: every shared sample model lit
# by quadra's defaults. Run it after a change to what a frame looks like.
# The models are looked for in ../shared/assets (or $QUADRA_ASSETS).
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/bin/quadra ] || bash scripts/build.sh quadra
Q=build/bin/quadra
assets=${QUADRA_ASSETS:-../shared/assets}
mkdir -p docs/images/gallery
$Q render builtin:showcase --width 960 --height 540 --samples 4 \
  --out docs/images/showcase.png

# The gallery: each model's default scene from quadra's own framing, under
# the default environment (builtin:studio); the models that `quadra report
# lighting` scores also under the shared HDR panorama. A model quadra
# refuses gets its one-line reason instead of a picture.
size=(--width 320 --height 240 --samples 4)
garden=$assets/environments/chinese_garden_1k.hdr
scored=" WaterBottle BoomBoxWithAxes Avocado Suzanne NormalTangentMirrorTest MetalRoughSpheresNoTextures LightsPunctualLamp EmissiveStrengthTest CesiumMilkTruck "
rm -f docs/images/gallery/*.png
{
  echo "# Gallery: the shared sample models, lit"
  echo
  echo "Every glTF model of the shared sample assets (../shared/assets) as"
  echo "\`quadra render MODEL --width 320 --height 240 --samples 4 --out PNG\` draws it:"
  echo "quadra's defaults, \`--shading pbr\` under the built-in studio environment,"
  echo "the scene's KHR_lights_punctual lights, the PBR Neutral tone map, the"
  echo "scene's camera or quadra's framing. The models \`quadra report lighting\`"
  echo "scores are shown under the shared panorama too (\`--env chinese_garden_1k.hdr\`)."
  echo "Made by \`bash scripts/docs-images.sh\`."
  echo
  echo "| model | builtin:studio (default) | chinese_garden_1k.hdr |"
  echo "|---|---|---|"
} >docs/gallery.md
for dir in "$assets"/*/glTF; do
  model=$(basename "$(dirname "$dir")")
  file=$dir/$model.gltf
  [ -f "$file" ] || continue
  if ! error=$($Q render "$file" "${size[@]}" --out "docs/images/gallery/$model.png" 2>&1 >/dev/null); then
    echo "| $model | not rendered: \`${error#quadra: *: }\` | |" >>docs/gallery.md
    continue
  fi
  lit="![$model](images/gallery/$model.png)" garden_cell=""
  if [[ $scored == *" $model "* ]]; then
    $Q render "$file" "${size[@]}" --env "$garden" --out "docs/images/gallery/$model.garden.png" >/dev/null
    garden_cell="![$model under chinese_garden_1k](images/gallery/$model.garden.png)"
  fi
  echo "| $model | $lit | $garden_cell |" >>docs/gallery.md
done
