#!/usr/bin/env bash
# Render an rgmap.json: ./rgnav render <rgmap.json> --out map.svg|map.png [--export-pgm base]
set -euo pipefail
exec "$RGNAV_BUILD/bin/rgnav_render" "$@"
