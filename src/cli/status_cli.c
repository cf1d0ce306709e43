/* rollsim status FILE.nc...: how far each sweep file got (io/sweep_status.h). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>

#include "io/sweep_status.h"
#include "cli/cli.h"

int rs_cli_status(int argc, char **argv)
{
  if (argc >= 1 && (!strcmp(argv[0], "--help") || !strcmp(argv[0], "-h"))) {
    rs_cli_help("status", stdout);
    return RS_OK;
  }
  if (argc < 1) {
    fprintf(stderr, "rollsim status: usage: rollsim status FILE.nc...\n");
    return RS_ERR_INPUT;
  }
  int status = RS_OK;
  for (int i = 0; i < argc; i++) {
    if (argv[i][0] == '-') {
      fprintf(stderr, "rollsim status: unknown option '%s'\n", argv[i]);
      return RS_ERR_INPUT;
    }
    rs_sweep_file_status st;
    rs_msg msg = {{0}};
    if (rs_sweep_file_status_read(argv[i], &st, &msg) != RS_OK) {
      fprintf(stderr, "rollsim status: %s\n", msg.text);
      status = RS_ERR_INPUT;
      continue;
    }
    char line[512];
    rs_sweep_file_status_line(&st, line, sizeof line);
    if (argc > 1)
      printf("%s: %s\n", argv[i], line);
    else
      printf("%s\n", line);
  }
  return status;
}
