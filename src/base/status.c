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

const char *rs_final_status(int status, const rs_msg *msg, char buf[RS_FINAL_STATUS_LEN])
{
  if (status == RS_OK)
    snprintf(buf, RS_FINAL_STATUS_LEN, "complete");
  else if (status == RS_ERR_INTERRUPTED)
    snprintf(buf, RS_FINAL_STATUS_LEN, "interrupted");
  else
    snprintf(buf, RS_FINAL_STATUS_LEN, "failed: %s", msg->text);
  return buf;
}
