#!/usr/bin/env bash
# Unpacks (never installs) Debian's python3-paraview into DEST, at the version of
# the installed paraview-dev: its files are needed to build and test the plugin, but
# installing it would remove libvtk9-dev (CausticsDebianParaView.cmake says why).
#
#   unpack-python3-paraview.sh DEST
set -euo pipefail
dest=${1:?usage: unpack-python3-paraview.sh DEST}
if [ -f "$dest/usr/lib/python3/dist-packages/paraview/simple.py" ]; then
  exit 0
fi
version=$(dpkg-query -W -f='${Version}' paraview-dev)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# apt's cache first; else the exact version, named explicitly so that a pin keeping
# python3-paraview off the machine (priority -1) does not stop the download.
cached="/var/cache/apt/archives/python3-paraview_${version//:/%3a}_amd64.deb"
if [ -f "$cached" ]; then
  cp "$cached" "$work/"
else
  (cd "$work" && apt-get download -q "python3-paraview=$version")
fi
rm -rf "$dest"
mkdir -p "$dest"
dpkg-deb -x "$work"/python3-paraview_*.deb "$dest"
echo "unpack-python3-paraview: python3-paraview $version unpacked into $dest"
