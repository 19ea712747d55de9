# Sourced by the navigation benchmarks (localize, plan, explore) after they set ROOT and ONLY
# (their *_ONLY variable: space-separated world names, empty for all). Their worlds: the office
# world and four IPA building maps of different kinds (a lab, an institute floor, a furnished
# lab, an office floor), from ../shared/data (RGNAV_DATA).
#   wanted NAME       true when ONLY is empty or lists NAME
#   nav_world_args    fills the array `world_args` with --sim NAME=PATH for each wanted world
SHARED="${RGNAV_DATA:-$ROOT/../shared/data}"
IPA="$SHARED/maps/ipa"

wanted() { [ -z "$ONLY" ] || [[ " $ONLY " == *" $1 "* ]]; }

nav_world_args() {
  local spec
  local specs=("office=$ROOT/config/worlds/office.yaml" "lab_ipa=$IPA/lab_ipa.png"
               "Freiburg52=$IPA/Freiburg52_scan.png" "lab_c_furnished=$IPA/lab_c_scan_furnitures.png"
               "office_e=$IPA/office_e.png")
  world_args=()
  for spec in "${specs[@]}"; do
    if wanted "${spec%%=*}"; then world_args+=(--sim "$spec"); fi
  done
}
