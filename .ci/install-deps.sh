#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs every package rtcl builds, tests and benchmarks with (Debian 12, as root).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends \
    build-essential cmake ninja-build pkg-config git ca-certificates \
    ocl-icd-opencl-dev opencl-c-headers pocl-opencl-icd clinfo oclgrind \
    libvulkan-dev mesa-vulkan-drivers glslang-tools spirv-tools vulkan-validationlayers \
    libsdl2-dev xvfb xauth \
    libopenimageio-dev openimageio-tools \
    libsimde-dev libembree-dev libjansson-dev \
    libtinygltf-dev nlohmann-json3-dev libstb-dev \
    gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user \
    clang libclang-rt-14-dev clang-format gnuplot-nox python3 ffmpeg time help2man \
    python3-dev python3-numpy python3-pytest python3-open3d >/dev/null
echo "dependencies installed"
