#!/usr/bin/env bash
# `cmake --install` into a temporary prefix, then check_installed.sh on it (ctest install.prefix).
# Usage: install_test.sh BUILD_DIR
set -euo pipefail
build=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/sylva-install-XXXXXX")
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
"$(dirname "$0")/check_installed.sh" "$work/prefix" "$work"
