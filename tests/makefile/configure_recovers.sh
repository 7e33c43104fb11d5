#!/bin/sh
# The Makefile must recover from a failed first configure (issue 14): run the project's Makefile on a
# scratch project whose first configure fails (as when packages are missing), then fix the cause and
# run make again: it must configure and build without `make clean`.
#   configure_recovers.sh <project Makefile> <scratch folder>
set -u
makefile=$1
work=$2
rm -rf "$work" && mkdir -p "$work" || exit 1
cp "$makefile" "$work/Makefile"
cat > "$work/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.18)
project(scratch NONE)
if(EXISTS ${CMAKE_SOURCE_DIR}/missing-package)
  message(FATAL_ERROR "a required package is missing")
endif()
add_custom_target(hello ALL COMMAND ${CMAKE_COMMAND} -E touch ${CMAKE_BINARY_DIR}/built)
CMAKE
touch "$work/missing-package"
if make -C "$work" build CMAKE_FLAGS= >"$work/first.log" 2>&1; then
    echo "FAIL: the first configure should have failed"; exit 1
fi
rm "$work/missing-package"   # the user installs the packages
if ! make -C "$work" build CMAKE_FLAGS= >"$work/second.log" 2>&1; then
    echo "FAIL: make did not recover after the failed configure:"; cat "$work/second.log"; exit 1
fi
[ -f "$work/build/built" ] || { echo "FAIL: the build did not run"; exit 1; }
echo "ok: a failed configure is retried by the next make"
rm -rf "$work"
