#!/usr/bin/env bash
# Copyright 2026 stewart_kinematics developers
# SPDX-License-Identifier: Apache-2.0
#
# Build the interface package tf2_msgs (msg/TFMessage only, from test/resources/tf2_msgs/) into
# a venv, so that the nodes' /tf and /tf_static broadcasts are tested for real where ROS is not
# installed: tf2_msgs is not on PyPI, but the rosidl tools are (requirements.txt pins them), and
# the message has the same wire type as upstream's. A ROS installation has the real tf2_msgs;
# this stand-in is never shipped (test/resources/ carries a COLCON_IGNORE).
#
# Usage: scripts/build_tf2_msgs.sh [VENV]   (default: .venv/ in the repository root)
#
# Steps: rewrite the build machine's paths that the ROS wheels' CMake exports hard-code
# (/opt/python/cp3XX-cp3XX/include/python3.X and its numpy include folder) to this venv's, then
# configure, build and install the package into the venv's prefix with CMake, as colcon would
# (the venv's lib/ is on the library path that the ROS wheels' start-up hook sets).
#
# Idempotent: does nothing when tf2_msgs imports in the venv and its sources, this script and the
# Python version are unchanged since the last build (a hash in VENV/.tf2_msgs_stamp). Quiet:
# the build's output is shown only when it fails.

set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$(cd "${1:-${root}/.venv}" && pwd)"
python="${venv}/bin/python"
source_directory="${root}/test/resources/tf2_msgs"
stamp="${venv}/.tf2_msgs_stamp"

fail() {
    echo "build_tf2_msgs.sh: $*" >&2
    exit 1
}

[[ -x "${python}" ]] || fail "no venv at ${venv} (run scripts/setup_venv.sh)"
for tool in cmake make cc; do
    command -v "${tool}" >/dev/null 2>&1 \
        || fail "${tool} is needed to build tf2_msgs (apt-get install cmake build-essential)"
done

# Hash of everything the build depends on.
build_hash() {
    "${python}" - "${BASH_SOURCE[0]}" "${source_directory}" <<'PYTHON'
import hashlib
import pathlib
import sys

digest = hashlib.sha256(sys.version.encode())
paths = [pathlib.Path(sys.argv[1])] + sorted(
    path for path in pathlib.Path(sys.argv[2]).rglob('*') if path.is_file())
for path in paths:
    digest.update(path.name.encode() + b'\0' + path.read_bytes() + b'\0')
print(digest.hexdigest())
PYTHON
}

if [[ -f "${stamp}" ]] && [[ "$(cat "${stamp}")" == "$(build_hash)" ]] \
        && "${python}" -c 'from tf2_msgs.msg import TFMessage' >/dev/null 2>&1; then
    exit 0
fi
rm -f "${stamp}"
start=${SECONDS}

python_include="$("${python}" -c 'import sysconfig; print(sysconfig.get_paths()["include"])')"
numpy_include="$("${python}" -c 'import numpy; print(numpy.get_include())')"
# The wheels were built in a manylinux image with Python in /opt/python/cp3XX-cp3XX (grep finds
# nothing once rewritten).
{ grep -rlE --include='*.cmake' '/opt/python/cp3[0-9]+-cp3[0-9]+/' "${venv}/share" || true; } \
    | xargs -r sed -i -E \
        -e "s#/opt/python/cp3[0-9]+-cp3[0-9]+/lib/python3\.[0-9]+/site-packages/numpy/_core/include#${numpy_include}#g" \
        -e "s#/opt/python/cp3[0-9]+-cp3[0-9]+/include/python3\.[0-9]+#${python_include}#g"

build_directory="$(mktemp -d)"
log="$(mktemp)"
trap 'rm -rf "${build_directory}" "${log}"' EXIT
if ! {
    export PATH="${venv}/bin:${PATH}" AMENT_PREFIX_PATH="${venv}" CMAKE_PREFIX_PATH="${venv}"
    cmake -S "${source_directory}" -B "${build_directory}" -DCMAKE_INSTALL_PREFIX="${venv}" \
        -DPython3_EXECUTABLE="${python}" -DBUILD_TESTING=OFF \
        && cmake --build "${build_directory}" --parallel 2 \
        && cmake --install "${build_directory}"
} >"${log}" 2>&1; then
    cat "${log}" >&2
    fail 'building tf2_msgs failed (output above)'
fi
"${python}" -c 'from tf2_msgs.msg import TFMessage' \
    || fail "tf2_msgs was built but does not import in ${venv}"

build_hash >"${stamp}"
echo "build_tf2_msgs.sh: tf2_msgs/msg/TFMessage built into ${venv} ($((SECONDS - start)) s)"
