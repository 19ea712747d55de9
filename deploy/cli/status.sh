#!/usr/bin/env bash
# ./rgnav status [--once] [--host H]: the deputies' process table, refreshed each second
exec bash "$(dirname "$0")/lib/ctl.sh" status "$@"
