#!/usr/bin/env bash
# ./rgnav stop <process|group|everything> [--host H] [--wait]: stop through the deputies
exec bash "$(dirname "$0")/lib/ctl.sh" stop "$@"
