#!/usr/bin/env bash
# Fails when any C++ source differs from .clang-format.
set -euo pipefail
cd "$(dirname "$0")/.."
files=$(git ls-files '*.h' '*.cpp')
clang-format --dry-run --Werror $files
