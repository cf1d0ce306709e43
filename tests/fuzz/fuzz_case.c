/* libFuzzer target for the case-file parser (src/case*.c): the input bytes are written to
 * a case file and loaded with rs_case_load, once as they are, once with --set overrides,
 * and once with the first "#set KEY=VALUE" comment line of the input as a --set, so the
 * --set parser is fuzzed too. A loaded case is printed (as `rollsim check` does) and
 * freed. Crashes, leaks (LeakSanitizer), undefined behaviour, and a case not left
 * freed/zeroed after an error fail the run.
 *
 * Built and run by .ci/fuzz:
 *   clang -fsanitize=fuzzer,address,undefined -Iinclude tests/fuzz/fuzz_case.c \
 *         src/case*.c src/history.c src/status.c -lyaml -lm
 *   fuzz_case -max_total_time=60 WORK_CORPUS tests/fuzz/corpus */
#define _DEFAULT_SOURCE /* mkstemps */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/case.h"

/* Rewritten for every input: in /dev/shm (tmpfs) when there is one, as on ext4 each rewrite
 * of a truncated file is flushed to disk on close (auto_da_alloc) and the fuzzer would
 * mostly wait for the disk. */
static char case_path[64];
static FILE *devnull;

static void remove_case_file(void) { unlink(case_path); }

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
  (void)argc;
  (void)argv;
  struct stat st;
  int fd = -1;
  if (stat("/dev/shm", &st) == 0 && S_ISDIR(st.st_mode)) {
    snprintf(case_path, sizeof case_path, "/dev/shm/rs_fuzz_case_XXXXXX.yaml");
    fd = mkstemps(case_path, 5);
  }
  if (fd < 0) {
    snprintf(case_path, sizeof case_path, "/tmp/rs_fuzz_case_XXXXXX.yaml");
    fd = mkstemps(case_path, 5);
  }
  if (fd < 0) {
    perror("fuzz_case: mkstemps");
    abort();
  }
  close(fd);
  atexit(remove_case_file);
  devnull = fopen("/dev/null", "w");
  if (!devnull) abort();
  return 0;
}

static void load(const char *const *sets, int nsets)
{
  rs_case c;
  rs_msg msg = {{0}};
  int status = rs_case_load(&c, case_path, sets, nsets, &msg);
  if (status == RS_OK) {
    rs_case_print(&c, devnull);
  } else if (status != RS_ERR_INPUT || msg.text[0] == '\0' || c.yaml_text || c.title ||
             c.output_file || c.source_path || c.normal_load.t || c.creepage.t || c.velocity.t ||
             c.shift_velocity.t) {
    /* rs_case_load's contract: an error says what and leaves the case freed/zeroed */
    fprintf(stderr, "fuzz_case: status %d, message \"%s\"\n", status, msg.text);
    abort();
  }
  rs_case_free(&c);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FILE *f = fopen(case_path, "wb");
  if (!f) abort();
  if (size && fwrite(data, 1, size, f) != size) abort();
  fclose(f);

  load(NULL, 0);

  static const char *const sets[] = {
      "grid.cells=50",
      "rolling.creepage={ramp: {from: 0.0, to: -0.01, start: 0.0, duration: 0.05}}",
      "plasticity.k_rel=0.6",
  };
  load(sets, 3);

  /* A comment line "#set KEY=VALUE" in the input is passed as a --set too (main() passes on
   * only arguments with a '='): the file stays valid YAML and the --set parser is fuzzed. */
  for (size_t i = 0; i + 5 <= size; i++) {
    if ((i > 0 && data[i - 1] != '\n') || memcmp(data + i, "#set ", 5)) continue;
    const uint8_t *start = data + i + 5;
    const size_t rest = size - (i + 5);
    const uint8_t *eol = memchr(start, '\n', rest);
    const size_t len = eol ? (size_t)(eol - start) : rest;
    if (len > 0 && len < 512 && memchr(start, '=', len) && !memchr(start, '\0', len)) {
      char set[512];
      memcpy(set, start, len);
      set[len] = '\0';
      const char *one[] = {set};
      load(one, 1);
    }
    break;
  }
  return 0;
}
