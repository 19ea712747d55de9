#!/usr/bin/env bash
# ./rgnav shutdown [--host H] [--wait]: stop every process and the deputies
exec bash "$(dirname "$0")/lib/ctl.sh" shutdown "$@"
