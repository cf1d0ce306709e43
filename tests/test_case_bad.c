/* A malformed or out-of-range case file is rejected with RS_ERR_INPUT and a
 * message that names the file, the line and the key.
 *
 * Usage: test_case_bad FILE.yaml
 * The file's leading comment lines say what to expect:
 *   # expect: TEXT   (one or more; each TEXT must appear in the message, normally the dotted key)
 *   # line: N        (optional; the message must contain "FILE:N:")
 * Without "# line:", the message must still contain "FILE:<digits>:". */
#include "io/case.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_EXPECT 8

int main(int argc, char **argv)
{
  if (argc != 2) {
    fprintf(stderr, "usage: %s FILE.yaml\n", argv[0]);
    return 2;
  }
  const char *path = argv[1];
  FILE *f = fopen(path, "rb");
  if (!f) {
    perror(path);
    return 2;
  }
  char expect[MAX_EXPECT][512], line[512];
  int nexpect = 0;
  long want_line = -1;
  while (fgets(line, sizeof line, f) && line[0] == '#') {
    line[strcspn(line, "\r\n")] = '\0';
    if (!strncmp(line, "# expect: ", 10) && nexpect < MAX_EXPECT)
      snprintf(expect[nexpect++], sizeof expect[0], "%s", line + 10);
    else if (!strncmp(line, "# line: ", 8))
      want_line = strtol(line + 8, NULL, 10);
  }
  fclose(f);
  if (nexpect == 0) {
    fprintf(stderr, "%s: no '# expect: KEY' comment on the first line\n", path);
    return 2;
  }

  rs_case c;
  rs_msg msg = {{0}};
  int status = rs_case_load(&c, path, NULL, 0, &msg);
  printf("%s\n  -> status %d: %s\n", path, status, msg.text);
  int failures = 0;
  if (status != RS_ERR_INPUT) {
    printf("FAIL: status %d, want RS_ERR_INPUT (%d)\n", status, RS_ERR_INPUT);
    failures++;
  }
  if (c.yaml_text || c.title || c.output_file || c.source_path || c.normal_load.t) {
    printf("FAIL: the case is not left freed/zeroed after an error\n");
    failures++;
  }
  for (int i = 0; i < nexpect; i++)
    if (!strstr(msg.text, expect[i])) {
      printf("FAIL: message does not contain \"%s\"\n", expect[i]);
      failures++;
    }
  char where[600];
  if (want_line > 0) {
    snprintf(where, sizeof where, "%s:%ld: ", path, want_line);
    if (strncmp(msg.text, where, strlen(where))) {
      printf("FAIL: message does not start with \"%s\"\n", where);
      failures++;
    }
  } else {
    size_t len = strlen(path);
    const char *p = msg.text + len;
    int ok = !strncmp(msg.text, path, len) && *p == ':' && p[1] >= '0' && p[1] <= '9';
    for (p++; ok && *p >= '0' && *p <= '9'; p++)
      ;
    if (!ok || *p != ':') {
      printf("FAIL: message does not start with \"%s:<line>:\"\n", path);
      failures++;
    }
  }
  return failures ? 1 : 0;
}
