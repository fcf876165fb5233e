#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# minimal_build.sh - the build without the optional libraries (jansson,
# OpenImageIO, Embree, tinygltf), as a machine that has only a C compiler, CMake and
# SIMDe gets it: it must build, render OBJ scenes to PPM/PFM, refuse JSON
# scenes and PNG with the reason, and install a usable library.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-minimal}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRT_WERROR=ON \
    -DRT_JANSSON=OFF -DRT_OIIO=OFF -DRT_GLTF=OFF -DRT_EMBREE=OFF -DRT_VULKAN=OFF -DRT_VIEW=OFF
cmake --build "$build" -j "$(nproc)"
rtcl="$build/rtcl"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if ldd "$rtcl" | grep -i -E 'jansson|OpenImageIO|embree|tbb|tinygltf'; then
    echo "FAIL: the minimal rtcl links an optional library"; exit 1
fi
"$rtcl" render scenes/cornell_room.obj --width 64 --height 36 -o "$tmp/room.ppm"
"$rtcl" render scenes/cornell_room.obj --width 64 --height 36 --aov depth -o "$tmp/depth.pfm"
"$rtcl" compare "$tmp/room.ppm" "$tmp/room.ppm"
"$rtcl" info scenes/cornell_room.obj >/dev/null
if "$rtcl" info scenes/cornell.json 2>"$tmp/err"; then echo "FAIL: JSON loaded without jansson"; exit 1; fi
grep -q 'no JSON scene loader' "$tmp/err" || { echo "FAIL: unclear JSON error:"; cat "$tmp/err"; exit 1; }
if "$rtcl" render scenes/cornell_room.obj -o "$tmp/x.png" 2>"$tmp/err"; then
    echo "FAIL: PNG written without OpenImageIO"; exit 1
fi
grep -q 'no PNG or EXR support' "$tmp/err" || { echo "FAIL: unclear PNG error:"; cat "$tmp/err"; exit 1; }
glb=tests/fuzz/corpus/gltf/animated.glb
if "$rtcl" info "$glb" 2>"$tmp/err"; then echo "FAIL: glTF loaded without tinygltf"; exit 1; fi
grep -q "animated.glb.*no glTF support" "$tmp/err" || { echo "FAIL: unclear glTF error:"; cat "$tmp/err"; exit 1; }
# The tests that need no optional part, the install and ray queries among them.
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" -R 'test_core_|cli_install|cli_trace|cli_startup|cli_bench_incoherent|cli_shared_symbols'
echo "minimal build: ok"
