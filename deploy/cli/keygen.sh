#!/usr/bin/env bash
# ./rgnav keygen [--force] [--key FILE]: make the shared key that signs supervisor orders
# The key file (config/supervisor.yaml orders.key_file; by default /etc/rgnav/orders.key if it
# exists, else ~/.config/rgnav/orders.key) is written with mode 600. Copy the same file to every
# deputy and controller host: orders signed with another key are refused. An existing key is
# kept unless --force.
exec "${RGNAV_BUILD:-$(cd "$(dirname "$0")/../.." && pwd)/build}/bin/rgnav_ctl" keygen "$@"
