#!/bin/sh
# Builds ompl_p2p and spaces_check next to this script. Needs g++, pkg-config and libompl-dev (OMPL 1.5,
# which brings Eigen and Boost headers): apt-get install -y libompl-dev
set -eu
here=$(cd "$(dirname "$0")" && pwd)
cflags=$(pkg-config --cflags ompl 2>/dev/null || echo "-I/usr/include/ompl-1.5 -I/usr/include/eigen3")
# Debian's ompl.pc lists Boost libraries by absolute path and a broken -L; libompl.so
# carries its own dependencies, so -lompl is enough.
set -x
${CXX:-g++} -std=c++17 -O2 -Wall -Wextra $cflags "$here/ompl_p2p.cpp" -o "$here/ompl_p2p" -lompl
${CXX:-g++} -std=c++17 -O2 -Wall -Wextra $cflags "$here/spaces_check.cpp" -o "$here/spaces_check" -lompl
