/* commands.h - one function per rtcl command, each in its own cmd_*.c file.
 * Each gets argv after the command name (argv[0] is the command) and returns
 * the process exit status: 0 success, 1 a failed check (compare over the
 * limit), 2 a usage error or a failure. */
#ifndef RTCL_COMMANDS_H
#define RTCL_COMMANDS_H

int cmd_render(int argc, char **argv);
int cmd_info(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_trace(int argc, char **argv);
int cmd_generate(int argc, char **argv);
int cmd_devices(int argc, char **argv);
int cmd_animate(int argc, char **argv);
int cmd_view(int argc, char **argv);

#endif /* RTCL_COMMANDS_H */
