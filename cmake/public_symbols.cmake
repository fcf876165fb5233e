# SPDX-License-Identifier: Apache-2.0
# public_symbols.cmake - writes the linker version script of librtcl.so from
# the public header: every function declared in rt.h (comments removed, any
# name rt_xxx followed by '(') is global, everything else local, so that the
# shared library exports the public API and nothing of the library's inside.
# Run at build time: cmake -DHEADER=host/rt.h -DOUTPUT=rtcl.map -P this file.
file(READ "${HEADER}" text)
# /* ... */ comments (a star run not followed by '/' stays inside), then //.
string(REGEX REPLACE "/\\*([^*]|\\*+[^*/])*\\*+/" "" text "${text}")
string(REGEX REPLACE "//[^\n]*" "" text "${text}")
string(REGEX MATCHALL "rt_[A-Za-z0-9_]+[ \t\n]*\\(" calls "${text}")
set(names "")
foreach(c ${calls})
  string(REGEX REPLACE "[ \t\n]*\\($" "" n "${c}")
  list(APPEND names "${n}")
endforeach()
list(REMOVE_DUPLICATES names)
list(SORT names)
list(LENGTH names count)
if(count LESS 10)
  message(FATAL_ERROR "public_symbols.cmake: only ${count} functions found in ${HEADER}")
endif()
set(out "/* Generated from ${HEADER} by cmake/public_symbols.cmake: do not edit. */\n{\n  global:\n")
foreach(n ${names})
  string(APPEND out "    ${n};\n")
endforeach()
string(APPEND out "  local:\n    *;\n};\n")
# Rewritten only when it changes, so that an edit of rt.h's comments does not relink.
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
  if(old STREQUAL out)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${out}")
