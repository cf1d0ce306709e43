/* rs_msg: the error-message buffer (base/status.h). */
#include "base/status.h"

#include <stdarg.h>
#include <stdio.h>

int rs_msg_set(rs_msg *msg, int status, const char *fmt, ...)
{
  if (msg) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg->text, sizeof msg->text, fmt, ap);
    va_end(ap);
  }
  return status;
}
