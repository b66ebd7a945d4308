#!/usr/bin/env bash
# Checks an installed sylva: PREFIX/bin/sylva, run from another working directory with no
# SYLVA_CODECS, renders a small sample tree to PNG, TIFF (the codecs plugin) and MP4 (the plugin's
# FFmpeg), and each output is what it says (ffprobe reads the MP4's frames); `--version
# --verbose` names the plugin under PREFIX; the man page is there and renders without warnings;
# the presets are there. Used by install_test.sh and deb_test.sh.
# Usage: check_installed.sh PREFIX WORK_DIR
set -euo pipefail
prefix=$1
work=$2
sylva="$prefix/bin/sylva"
fail() {
  echo "check_installed: $*" >&2
  exit 1
}
unset SYLVA_CODECS
export SYLVA_CACHE_DIR="$work/cache"
mkdir -p "$work/run"
cd "$work/run"

[ -x "$sylva" ] || fail "$sylva is not an executable"
version=$("$sylva" --version)
echo "$version"
[[ $version =~ ^sylva\ [0-9]+\.[0-9]+\.[0-9]+\ \(commit\ [0-9a-z-]+\)$ ]] || fail "--version: $version"
verbose=$("$sylva" --version --verbose)
plugin=$(sed -n 's/^codecs plugin *//p' <<<"$verbose")
[[ $plugin == "$prefix"/lib/*sylva/libsylva_codecs.so\ * ]] || fail "the plugin loaded is not the installed one: $plugin"
grep -q '^OpenGL .*Mesa' <<<"$verbose" || fail "no GL renderer in --version --verbose: $verbose"

"$sylva" sample tree --seed 1 --leaves 300 -o tree.glb
"$sylva" render tree.glb --style toon --size 96 -o tree.png
"$sylva" render tree.glb --style ink --size 96 -o tree.tiff
"$sylva" turntable tree.glb --style toon --frames 6 --size 64 -q -o tree.mp4
[ "$(head -c 8 tree.png | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "tree.png is not a PNG"
case "$(head -c 4 tree.tiff | od -An -tx1 | tr -d ' \n')" in
  49492a00 | 4d4d002a) ;;
  *) fail "tree.tiff is not a TIFF" ;;
esac
probe=$(ffprobe -v error -count_frames -select_streams v:0 \
  -show_entries stream=codec_name,width,height,nb_read_frames -of csv=p=0 tree.mp4)
[ "$probe" = "h264,64,64,6" ] || fail "tree.mp4: ffprobe says '$probe', not h264,64,64,6"

man=$(find "$prefix/share/man/man1" -name 'sylva.1*' | head -n 1)
[ -n "$man" ] || fail "no man page under $prefix/share/man/man1"
warnings=$(LC_ALL=C.UTF-8 MANWIDTH=80 man --warnings -E UTF-8 -l "$man" 2>&1 >/dev/null)
[ -z "$warnings" ] || fail "man page warnings: $warnings"
LC_ALL=C.UTF-8 man -l "$man" 2>/dev/null | grep -q -- '--frame-range' || fail "the man page lacks --frame-range"
for style in standard expressive ink pen toon watercolor blobs; do
  [ -f "$prefix/share/sylva/presets/$style.toml" ] || fail "no preset $style.toml"
done

# The Python module (when built): importable from its installed folder alone, it renders, and it
# finds the installed codecs plugin for TIFF.
module=$(find "$prefix/lib" -name '_sylva*.so' | head -n 1)
if [ -n "$module" ]; then
  PREFIX=$prefix PYTHONPATH=$(dirname "$(dirname "$module")") /usr/bin/python3 -c '
import os, sylva
img = sylva.render(sylva.load("tree.glb"), "toon", size=64)
assert img.shape == (64, 64, 4), img.shape
sylva.save(img, "py.tiff")
assert os.environ["SYLVA_CODECS"].startswith(os.environ["PREFIX"]), os.environ["SYLVA_CODECS"]
' || fail "the installed Python module does not render"
  [ "$(head -c 4 py.tiff | od -An -tx1 | tr -d ' \n')" = 49492a00 ] || fail "py.tiff is not a TIFF"
fi
echo "check_installed: $prefix is complete (PNG, TIFF, MP4, man page, presets, Python)"
