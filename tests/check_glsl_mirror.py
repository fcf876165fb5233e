#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Every function of the shared maths has its GLSL mirror.

The shared maths is one header per job in kernels/ (C99 = OpenCL C); the
Vulkan shaders mirror each header kernels/rt_NAME.h in
kernels/vulkan/rt_vk_NAME.glsl, function by function, with the C function's
name (docs/ARCHITECTURE.md, "The shared maths, file by file"). This check
reads the function definitions of every pair (RT_FN, RT_FN_RARE and RT_SM_FN functions,
and the static inline helpers, in C; functions at the start of a line in
GLSL) and fails when
- a C function has no function of its name in its twin GLSL file, unless
  C_ONLY below lists it with the reason;
- a GLSL function has no C function of its name in its twin header, unless
  GLSL_ONLY lists it with the reason;
- a function of either list exists on both sides after all (the list is
  stale), or a listed function no longer exists at all;
- a shared maths header has no twin and is not in NO_TWIN, or a twin is
  missing;
- a numeric constant (#define RT_NAME number) that both files of a pair
  define has different values (C's f and u suffixes aside).

Usage: check_glsl_mirror.py SOURCE_ROOT [--self-test]. With --self-test it
also checks itself: it deletes a mirrored function from a copy of its GLSL
file and fails unless the check then fails (so the check cannot pass by
reading nothing). Exit 0 when everything is mirrored, 1 with each problem on
stdout."""
import os
import re
import shutil
import sys
import tempfile

# The shared maths headers without a GLSL twin, and why.
NO_TWIN = {
    "rt_fp_mode.h": "C only: the CPU thread's denormal mode (MXCSR, FPCR); the shaders take "
    "theirs from the SPIR-V float controls and SC_DENORM_FLUSH",
    "rt_shared.h": "an umbrella include (rt_camera.h + rt_trace.h), no functions of its own",
    "rt_kernel_args.h": "OpenCL only: the kernels' view arguments; its Vulkan twin is "
    "rt_vk_io.glsl (buffers, not functions)",
    "rt_kernel_arg_index.h": "OpenCL only: kernel argument positions",
    "rt_interface.h": "the C side of the GPU interface table (rt_interface.def); the GLSL "
    "side, rt_vk_interface.glsl, is generated from the same table",
    "rt_interface_rows.h": "the table's rows defined empty, for its expansions",
}

# C functions with no GLSL function of the same name, and why.
C_ONLY = {
    "rt_math_profile.h": {
        "rt_as_int_": "C's bit cast (memcpy); GLSL has floatBitsToInt",
        "rt_as_float_": "C's bit cast (memcpy); GLSL has intBitsToFloat",
    },
    "rt_camera.h": {
        "rt_camera_ray_at": "for callers that reuse a row's screen coordinates (the CPU packet "
        "path); the GLSL rt_camera_ray computes them itself, the same operations",
    },
    "rt_box.h": {
        "rt_box_test_bounds": "takes the box by pointer; GLSL has no pointers: rt_box_test reads "
        "the node by index and rt_inst_enter the instance box, each with the same slab steps",
    },
    "rt_hit.h": {
        "rt_hit_accepted_box": "takes the triangle's box by pointer (cpu_ref's single-ray tracer "
        "passes precomputed boxes); the GLSL rt_hit_accepted computes the box inline, the same "
        "operations",
    },
    "rt_shade.h": {
        "rt_shade_step": "one node of the shading tree; rt_vk_main.comp runs the steps "
        "(rt_shade_begin, rt_phong_light, rt_phong_add, rt_shade_end) around its one rt_trace call",
        "rt_shade_children": "the shading tree's stack: rt_vk_main.comp's loop",
        "rt_shade_hit": "the whole shading tree: rt_vk_main.comp's loop",
    },
    "rt_soft_math.h": {
        "rt_sm_bits_": "C's bit cast; GLSL works on uint bits throughout",
        "rt_sm_float_": "C's bit cast; GLSL works on uint bits throughout",
        "rt_soft_div_bits": "public wrapper of rt_sm_div_bits_; GLSL calls that from RT_DIV",
        "rt_soft_div_ftz_bits": "public wrapper of rt_sm_div_bits_ (flushing)",
        "rt_soft_sqrt_bits": "public wrapper of rt_sm_sqrt_bits_; GLSL calls that from RT_SQRT",
        "rt_soft_sqrt_ftz_bits": "public wrapper of rt_sm_sqrt_bits_ (flushing)",
        "rt_soft_diff_of_products_bits": "public wrapper of rt_sm_dop_bits_; GLSL calls that "
        "from RT_DOP",
        "rt_soft_diff_of_products_ftz_bits": "public wrapper of rt_sm_dop_bits_ (flushing)",
        "rt_soft_div": "float wrapper: RT_DIV in rt_vk_math_profile.glsl",
        "rt_soft_div_ftz": "float wrapper: RT_DIV with SC_DENORM_FLUSH",
        "rt_soft_sqrt": "float wrapper: RT_SQRT in rt_vk_math_profile.glsl",
        "rt_soft_sqrt_ftz": "float wrapper: RT_SQRT with SC_DENORM_FLUSH",
        "rt_soft_diff_of_products": "float wrapper: RT_DOP in rt_vk_math_profile.glsl",
        "rt_soft_diff_of_products_ftz": "float wrapper: RT_DOP with SC_DENORM_FLUSH",
    },
}

# GLSL functions with no C function of the same name, and why.
GLSL_ONLY = {
    "rt_vk_math_profile.glsl": {
        "RT_DIV": "a macro in C (rt_math_profile.h): the profile's division",
        "RT_SQRT": "a macro in C: the profile's square root",
        "RT_DOP": "a macro in C: the exact difference of products",
        "RT_FABS": "a macro in C (fabsf / fabs); here the sign bit cleared",
    },
    "rt_vk_tri_t.glsl": {
        "rt_tri_coord": "a triangle's coordinate by number, by selects: C indexes the "
        "struct's nine floats in a row",
    },
    "rt_vk_vec.glsl": {
        "rt_pick3": "an element by selects: drivers keep run-time indexed local arrays in "
        "scratch memory",
    },
}

C_FN = re.compile(r"^(?:RT_FN_RARE|RT_FN|RT_SM_FN|static\s+inline)\s+[\w\s\*]*?\b(\w+)\s*\(", re.M)
GLSL_FN = re.compile(r"^(?:float|void|bool|int|uint|rt_\w+)\s+(\w+)\s*\(", re.M)
CONST = re.compile(r"^#define\s+(RT_\w+)\s+([-+0-9.eExXa-fA-FuUf]+)\s*(?:/\*.*)?$", re.M)


def strip_comments(text):
    return re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)


def number(text):
    t = text.rstrip("uUfF") if not text.lower().startswith("0x") else text.rstrip("uU")
    try:
        return int(t, 0)
    except ValueError:
        return float(t)


def check(root):
    kernels = os.path.join(root, "kernels")
    glsl_dir = os.path.join(kernels, "vulkan")
    problems = []
    pairs = 0
    functions = 0
    headers = sorted(n for n in os.listdir(kernels) if re.match(r"rt_\w+\.h$", n))
    for h in headers:
        twin = "rt_vk_" + h[len("rt_"):-len(".h")] + ".glsl"
        has_twin = os.path.isfile(os.path.join(glsl_dir, twin))
        if h in NO_TWIN:
            if has_twin:
                problems.append(f"kernels/{h} is listed without a twin, but {twin} exists")
            continue
        if not has_twin:
            problems.append(f"kernels/{h} has no GLSL twin kernels/vulkan/{twin} "
                            "(mirror it, or list it in NO_TWIN with the reason)")
            continue
        pairs += 1
        c_text = strip_comments(open(os.path.join(kernels, h), encoding="utf-8").read())
        g_text = strip_comments(open(os.path.join(glsl_dir, twin), encoding="utf-8").read())
        c_fns = set(C_FN.findall(c_text))
        g_fns = set(GLSL_FN.findall(g_text))
        functions += len(c_fns)
        c_only = C_ONLY.get(h, {})
        g_only = GLSL_ONLY.get(twin, {})
        for f in sorted(c_fns - g_fns):
            if f not in c_only:
                problems.append(f"kernels/{h}: {f} has no mirror in kernels/vulkan/{twin}")
        for f in sorted(g_fns - c_fns):
            if f not in g_only:
                problems.append(f"kernels/vulkan/{twin}: {f} has no C function in kernels/{h}")
        for f in sorted(c_only):
            if f not in c_fns:
                problems.append(f"C_ONLY lists {f} of kernels/{h}, which has no such function")
            elif f in g_fns:
                problems.append(f"C_ONLY lists {f} of kernels/{h}, but {twin} mirrors it")
        for f in sorted(g_only):
            if f not in g_fns:
                problems.append(f"GLSL_ONLY lists {f} of {twin}, which has no such function")
            elif f in c_fns:
                problems.append(f"GLSL_ONLY lists {f} of {twin}, but kernels/{h} has it too")
        c_consts = dict(CONST.findall(c_text))
        g_consts = dict(CONST.findall(g_text))
        for name in sorted(set(c_consts) & set(g_consts)):
            if number(c_consts[name]) != number(g_consts[name]):
                problems.append(f"{name} is {c_consts[name]} in kernels/{h} but "
                                f"{g_consts[name]} in kernels/vulkan/{twin}")
    for h in list(NO_TWIN) + list(C_ONLY):
        if h not in headers:
            problems.append(f"the lists name kernels/{h}, which does not exist")
    for g in GLSL_ONLY:
        if not os.path.isfile(os.path.join(glsl_dir, g)):
            problems.append(f"GLSL_ONLY names kernels/vulkan/{g}, which does not exist")
    if pairs < 10 or functions < 50:
        problems.append(f"only {pairs} header pairs and {functions} C functions found: "
                        "the patterns no longer match the sources")
    return problems, pairs, functions


def self_test(root):
    """Removes rt_tri_moller from a copy's rt_vk_tri.glsl: the check must fail."""
    with tempfile.TemporaryDirectory() as tmp:
        shutil.copytree(os.path.join(root, "kernels"), os.path.join(tmp, "kernels"))
        path = os.path.join(tmp, "kernels", "vulkan", "rt_vk_tri.glsl")
        text = open(path, encoding="utf-8").read()
        cut = re.sub(r"^bool rt_tri_moller\(.*?^}\n", "", text, flags=re.S | re.M)
        if cut == text:
            return ["self-test: rt_tri_moller not found in rt_vk_tri.glsl to remove"]
        open(path, "w", encoding="utf-8").write(cut)
        problems, _, _ = check(tmp)
        want = "kernels/rt_tri.h: rt_tri_moller has no mirror in kernels/vulkan/rt_vk_tri.glsl"
        if want not in problems:
            return ["self-test: removing rt_tri_moller from the GLSL was not reported"]
    return []


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), ".."))
    problems, pairs, functions = check(root)
    if "--self-test" in sys.argv[2:]:
        problems += self_test(root)
    for p in problems:
        print("FAIL: " + p)
    if problems:
        return 1
    print(f"{pairs} header pairs, {functions} C functions: each mirrored in GLSL or listed "
          "with its reason")
    return 0


if __name__ == "__main__":
    sys.exit(main())
