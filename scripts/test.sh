#!/usr/bin/env bash
# Quick start 2: install what is missing, build, and run every test (ctest, 2 jobs) but the long
# stress suite (ctest -L stress, hours: run it on its own); then the core tests and the short fuzz
# runs again under AddressSanitizer and UndefinedBehaviorSanitizer (clang, build-sanitize/).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
ctest --test-dir "$root/build" -j2 --output-on-failure -LE stress
"$root/scripts/sanitize.sh" --ci
