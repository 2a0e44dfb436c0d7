#!/usr/bin/env bash
# Installs the Python package `erpt` (built by scripts/build.sh into build/python/erpt) into the
# interpreter's site-packages, with the renderer's library beside its compiled module (found
# through its $ORIGIN run path). Usage: scripts/install-python.sh [SITE_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
python=$(bash scripts/python.sh)
[ -f build/python/erpt/__init__.py ] || bash scripts/build.sh
site=${1:-$("$python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')}
mkdir -p "$site/erpt"
cp build/python/erpt/*.py build/python/erpt/_erpt*.so "$site/erpt/"
cp -L build/liberpt_core.so build/liberpt_oiio.so "$site/erpt/"  # the OpenImageIO module is found beside the library
echo "installed erpt into $site/erpt ($python -c 'import erpt')"
