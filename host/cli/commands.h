/* SPDX-License-Identifier: Apache-2.0 */
/* commands.h - one function per rtcl command, each in its own cmd_*.c file
 * with its option table (cli_options.h). Each function gets argv after the
 * command name (argv[0] is the command) and returns the process exit
 * status: 0 success, 1 a failed check (compare over the limit), 2 a usage
 * error or a failure. */
#ifndef RTCL_COMMANDS_H
#define RTCL_COMMANDS_H

#include "cli_options.h"

int cmd_render(int argc, char **argv);
int cmd_info(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_trace(int argc, char **argv);
int cmd_generate(int argc, char **argv);
int cmd_devices(int argc, char **argv);
int cmd_animate(int argc, char **argv);
int cmd_view(int argc, char **argv);

/* Their tables: operands, options, help. */
extern const cli_command cmd_render_spec, cmd_info_spec, cmd_compare_spec, cmd_bench_spec,
    cmd_trace_spec, cmd_generate_spec, cmd_devices_spec, cmd_animate_spec, cmd_view_spec;

#endif /* RTCL_COMMANDS_H */
