#!/usr/bin/env bash
# Installs Debian packages for CI's steps (QEMU for the firmware, Chromium for the report
# pages): `apt-get update`, then `apt-get install` of the packages named, non-interactive,
# through sudo where not root. The callers install only what they find missing.
# Usage: .ci/apt_install.sh PACKAGE...
set -euo pipefail
sudo=""
if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
$sudo env DEBIAN_FRONTEND=noninteractive apt-get update -qq
$sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    "$@" </dev/null
