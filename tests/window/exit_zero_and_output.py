#!/usr/bin/env python3
"""Runs a command and passes only when it exits 0 and its output matches PATTERN.

ctest's PASS_REGULAR_EXPRESSION ignores the exit status: a window session that printed its display
path and then failed (a script error at quit, an error after the screenshots) passed with it.

usage: exit_zero_and_output.py PATTERN -- COMMAND ARGS...
"""
import re
import subprocess
import sys

pattern, separator, command = sys.argv[1], sys.argv[2], sys.argv[3:]
if separator != "--" or not command:
    sys.exit(__doc__)
r = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
sys.stdout.write(r.stdout)
if r.returncode != 0:
    sys.exit(f"exit status {r.returncode}, expected 0")
if not re.search(pattern, r.stdout):
    sys.exit(f"the output lacks /{pattern}/")
