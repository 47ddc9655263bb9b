#!/usr/bin/python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""The README's configuration table against the flags dot-server defines.

Every flag `dot-server --help` lists (but --help and --version) and its
environment variable must have a row in README.md's "## Configuration"
table, and every flag or variable the table names must exist: the table
cannot drift from the flag definitions.
    config_table_test.py DOT_SERVER README.md
"""
import re
import subprocess
import sys


def main(server, readme):
    help_text = subprocess.run([server, "--help"], check=True,
                               capture_output=True, text=True).stdout
    flags = set(re.findall(r"(?<![\w-])(--[a-z][a-z0-9-]+)", help_text))
    flags -= {"--help", "--version"}
    envs = set(re.findall(r"\b(DOT_[A-Z0-9_]+)\b", help_text))
    text = open(readme, encoding="utf-8").read()
    section = text[text.index("\n## Configuration"):]
    section = section[:section.index("\n## ", 1)]
    rows = [line for line in section.splitlines()
            if line.startswith("| `--")]
    table_flags, table_envs = set(), set()
    for row in rows:
        cells = row.split("|")
        table_flags |= set(re.findall(r"`(--[a-z0-9-]+)`", cells[1]))
        table_envs |= set(re.findall(r"`(DOT_[A-Z0-9_]+)`", cells[2]))
    problems = []
    for f in sorted(flags - table_flags):
        problems.append(f"flag {f} has no row in the README's table")
    for f in sorted(table_flags - flags):
        problems.append(f"the README's table names {f}, which dot-server "
                        "does not define")
    for e in sorted(envs - table_envs):
        problems.append(f"variable {e} has no row in the README's table")
    for e in sorted(table_envs - envs):
        problems.append(f"the README's table names {e}, which dot-server "
                        "does not read")
    for p in problems:
        print("FAIL:", p)
    print(f"{len(flags)} flags, {len(envs)} variables, {len(rows)} rows: "
          f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
