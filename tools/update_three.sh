#!/bin/sh
# Vendor three.js for `ucsio view` at the version pinned below: the npm
# registry's package, its single-file minified ES module build and its licence,
# copied unchanged into src/ucsio/picture/three/. Run from the repository root
# after changing VERSION; the page inlines the file (ucsio/picture/page.py).
#
# 0.170.0 is the last release whose build/three.module.min.js is one file with
# no imports; from 0.171 the minified build is split in two (three.core.min.js
# imported by three.module.min.js) and from 0.18x there is no minified build.
set -eu
VERSION=0.170.0
DEST=src/ucsio/picture/three
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm pack --silent "three@$VERSION" >/dev/null && tar xzf "three-$VERSION.tgz")
cp "$work/package/build/three.module.min.js" "$DEST/three.module.min.js"
cp "$work/package/LICENSE" "$DEST/LICENSE"
echo "$VERSION" > "$DEST/VERSION"
sha256sum "$DEST/three.module.min.js"
