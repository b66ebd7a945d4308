#!/usr/bin/python3
"""Checks that each library sees only the headers of the libraries it may depend on (DESIGN.md
section 2: core <- npr <- passes <- styles <- studies; samples on core): for every pair of
folders, a file compiled with one library's own flags (taken from compile_commands.json)
includes a header of the other folder, and the preprocessor must find it exactly when the
dependency is allowed. Usage: include_layering.py BUILD_DIR SOURCE_DIR. Exit 0 when all pairs
behave, 1 with one line per pair that does not."""
import json
import os
import shlex
import subprocess
import sys
import tempfile

ALLOWED = {
    "core": {"core"},
    "npr": {"core", "npr"},
    "passes": {"core", "npr", "passes"},
    "samples": {"core", "samples"},
    "styles": {"core", "npr", "passes", "styles"},
    "studies": {"core", "npr", "passes", "styles", "studies"},
}


def flags_of(commands, source_dir, folder):
    """The include and define flags of the first source file compiled from `folder` (or of a
    unity batch of its library, SYLVA_UNITY_BUILD)."""
    prefix = os.path.join(source_dir, folder) + os.sep
    batch = os.sep + "CMakeFiles" + os.sep + "sylva_" + folder + ".dir" + os.sep + "Unity" + os.sep
    for c in commands:
        if (c["file"].startswith(prefix) and c["file"].endswith(".cpp")) or batch in c["file"]:
            args = c["arguments"] if "arguments" in c else shlex.split(c["command"])
            keep, i = [args[0]], 1
            while i < len(args):
                a = args[i]
                if a in ("-I", "-isystem", "-iquote", "-D", "-std"):
                    keep += args[i:i + 2]
                    i += 2
                    continue
                if a.startswith(("-I", "-isystem", "-D", "-std=")):
                    keep.append(a)
                i += 1
            return keep
    raise SystemExit(f"include_layering: no source of {folder}/ in compile_commands.json")


def a_header(source_dir, folder):
    headers = sorted(f for f in os.listdir(os.path.join(source_dir, folder)) if f.endswith(".h"))
    return f"{folder}/{headers[0]}"


def main():
    build_dir, source_dir = sys.argv[1], os.path.realpath(sys.argv[2])
    with open(os.path.join(build_dir, "compile_commands.json")) as f:
        commands = json.load(f)
    for c in commands:
        c["file"] = os.path.realpath(os.path.join(c["directory"], c["file"]))
    bad = []
    with tempfile.TemporaryDirectory() as tmp:
        for user in ALLOWED:
            flags = flags_of(commands, source_dir, user)
            for used in ALLOWED:
                probe = os.path.join(tmp, "probe.cpp")
                with open(probe, "w") as f:
                    f.write(f'#include "{a_header(source_dir, used)}"\n')
                found = subprocess.run(flags + ["-E", "-o", os.devnull, probe],
                                       cwd=tmp, capture_output=True).returncode == 0
                if found != (used in ALLOWED[user]):
                    bad.append(f"{user}/ {'sees' if found else 'does not see'} {used}/'s headers")
    for line in bad:
        print("include_layering: " + line)
    print(f"include_layering: {len(ALLOWED) ** 2 - len(bad)} of {len(ALLOWED) ** 2} pairs as DESIGN.md says")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
