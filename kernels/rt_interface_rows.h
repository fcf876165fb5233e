/* SPDX-License-Identifier: Apache-2.0 */
/* rt_interface_rows.h - every row macro of rt_interface.def defined empty:
 * an expansion of the table includes this, redefines the rows it wants and
 * includes the table (rt_interface.h, rt_kernel_arg_index.h,
 * kernels/vulkan/gen_interface.c). No include guard: it is included before
 * each expansion. */
#undef RT_VIEW_BUFFER
#undef RT_IO_BUFFER
#undef RT_VK_BUFFER
#undef RT_CL_BUFFER
#undef RT_CL_KERNEL
#undef RT_CL_ARG
#undef RT_CL_KERNEL_END
#undef RT_PUSH
#undef RT_SPEC
#undef RT_AOV
#undef RT_CONST
#define RT_VIEW_BUFFER(ID, name, type, form, binding, what)
#define RT_IO_BUFFER(ID, name, type, access, binding, what)
#define RT_VK_BUFFER(ID, name, type, binding, what)
#define RT_CL_BUFFER(ID, what)
#define RT_CL_KERNEL(ID, name, view)
#define RT_CL_ARG(KERNEL, ARG, name)
#define RT_CL_KERNEL_END(ID)
#define RT_PUSH(type, name)
#define RT_SPEC(NAME, id, value)
#define RT_AOV(NAME, code)
#define RT_CONST(NAME, value)
