#!/usr/bin/env bash
# ./rgnav tour <world> [--out FILE]: plans a collision-free closed tour that enters every
# reachable labelled region of the world and writes it as YAML (default:
# logs/tours/<world>_tour.yaml). Exit 1 if the tour could not be made collision-free.
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
if [[ $# -lt 1 || "$1" == -h || "$1" == --help ]]; then
  echo "usage: ./rgnav tour <world> [--out FILE] [--margin M]" >&2
  exit 2
fi
WORLD="$1"; shift
OUT=""
ARGS=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out) OUT="$2"; shift 2 ;;
    *) ARGS+=("$1"); shift ;;
  esac
done
if [[ -z "$OUT" ]]; then
  mkdir -p "$ROOT/logs/tours"
  OUT="$ROOT/logs/tours/$(basename "${WORLD%.*}")_tour.yaml"
fi
"$BUILD/bin/sim_tour" "$WORLD" --worlds-dir "$ROOT/config/worlds" --sim-config "$ROOT/config/sim.yaml" \
  --out "$OUT" "${ARGS[@]+"${ARGS[@]}"}"
echo "$OUT"
