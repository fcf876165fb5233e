/* json_out.h - writing JSON by hand on stdout (rtcl's --json outputs). */
#ifndef RTCL_JSON_OUT_H
#define RTCL_JSON_OUT_H

/* Prints s on stdout as a JSON string: quoted, with quotes, backslashes and
 * control characters escaped. */
void json_out_string(const char *s);

#endif
