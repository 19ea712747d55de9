#!/usr/bin/env bash
# ./rgnav start <process|group|everything> [--host H] [--wait]: start through the deputies
exec bash "$(dirname "$0")/lib/ctl.sh" start "$@"
