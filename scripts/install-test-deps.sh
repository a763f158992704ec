#!/usr/bin/env bash
# Installs what the test suite needs beyond the build: headless Chromium, used to check that the
# `tripath compare` report (index.html) loads in a browser without console errors.
set -euo pipefail
exec bash "$(dirname "$0")/install-deps.sh" chromium
