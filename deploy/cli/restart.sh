#!/usr/bin/env bash
# ./rgnav restart <process|group|everything> [--host H] [--wait]: restart through the deputies
exec bash "$(dirname "$0")/lib/ctl.sh" restart "$@"
