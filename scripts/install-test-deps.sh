#!/usr/bin/env bash
# Installs what the test suite needs beyond the build: headless Chromium, used to check that the
# `tripath compare` report (index.html) loads in a browser without console errors, and Python's
# venv module, in which python/tests/test_install.py imports the module `cmake --install` placed.
set -euo pipefail
exec bash "$(dirname "$0")/install-deps.sh" chromium python3-venv
