/* rollsim status codes and the error-message buffer shared by all modules.
 * Functions return an int status; on failure they write a message in the user's
 * terms (file:line, key, simulated time, cell) into an rs_msg buffer. */
#ifndef ROLLSIM_STATUS_H
#define ROLLSIM_STATUS_H

#include <stddef.h>

enum rs_status {
  RS_OK = 0,
  RS_ERR_INTERNAL = 1,    /* a bug or an unexpected library failure */
  RS_ERR_INPUT = 2,       /* invalid case or command line: nothing was run */
  RS_ERR_SOLVER = 3,      /* the solver failed: partial results kept */
  RS_ERR_INTERRUPTED = 4, /* SIGINT/SIGTERM: partial results kept */
  RS_ERR_OUTPUT = 5       /* output file could not be written (exit code 1) */
};

#define RS_MSG_LEN 1024
typedef struct rs_msg {
  char text[RS_MSG_LEN];
} rs_msg;

/* printf-style: set the message (overwrites) and return status. */
int rs_msg_set(rs_msg *msg, int status, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* The status attribute of a finished output file: "complete" (RS_OK), "interrupted"
 * (RS_ERR_INTERRUPTED) or "failed: <msg>". Returns buf. */
#define RS_FINAL_STATUS_LEN (RS_MSG_LEN + 16)
const char *rs_final_status(int status, const rs_msg *msg, char buf[RS_FINAL_STATUS_LEN]);

#endif
