#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""vulkan_spirv_check.py - checks that a SPIR-V module is in the portable
maths profile: no OpFDiv, no Sqrt or InverseSqrt (GLSL.std.450), no Float64
capability or 64-bit float type, and every float arithmetic instruction
decorated NoContraction. Reads `spirv-dis --raw-id` output on stdin.

    spirv-dis --raw-id M.spv | vulkan_spirv_check.py NAME

Exit 0 when the module passes, 1 with the offending lines otherwise."""
import re
import sys

ARITH = {"OpFNegate", "OpFAdd", "OpFSub", "OpFMul", "OpFDiv", "OpFRem", "OpFMod",
         "OpVectorTimesScalar", "OpMatrixTimesScalar", "OpVectorTimesMatrix",
         "OpMatrixTimesVector", "OpMatrixTimesMatrix", "OpOuterProduct", "OpDot"}

name = sys.argv[1] if len(sys.argv) > 1 else "module"
floats, no_contraction, problems, arith = set(), set(), [], []
for line in sys.stdin:
    line = line.strip()
    m = re.match(r"(%\d+) = (Op\w+)(.*)", line)
    op = m.group(2) if m else line.split()[0] if line else ""
    if op == "OpCapability" and "Float64" in line:
        problems.append("Float64 capability: " + line)
    if m and op == "OpTypeFloat":
        if m.group(3).split()[0] != "32":
            problems.append("a float type that is not 32-bit: " + line)
        floats.add(m.group(1))
    if m and op in ("OpTypeVector", "OpTypeMatrix") and m.group(3).split()[0] in floats:
        floats.add(m.group(1))
    d = re.match(r"OpDecorate (%\d+) NoContraction", line)
    if d:
        no_contraction.add(d.group(1))
    if op == "OpFDiv":
        problems.append("a float division: " + line)
    if op == "OpExtInst" and re.search(r"\b(Sqrt|InverseSqrt)\b", line):
        problems.append("a square root: " + line)
    if m and op in ARITH and m.group(3).split()[0] in floats:
        arith.append((m.group(1), line))
for rid, line in arith:
    if rid not in no_contraction:
        problems.append("no NoContraction: " + line)
for p in problems[:20]:
    print(f"{name}: {p}")
if problems:
    print(f"{name}: {len(problems)} problems in {len(arith)} float arithmetic instructions")
    sys.exit(1)
print(f"{name}: {len(arith)} float arithmetic instructions, all NoContraction; "
      "no OpFDiv, no Sqrt/InverseSqrt, no Float64")
