/* The subcommands of rollsim and their help (cli/cli.h). One table: `rollsim --help`
 * lists it, `rollsim CMD --help` (or `rollsim help CMD`) prints one entry; a new
 * subcommand adds an entry here and gets both. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "io/profile.h"

typedef struct rs_command_help {
  const char *name;
  const char *synopsis; /* after "rollsim " */
  const char *summary;  /* one line for the overview */
  const char *text;     /* what it does, its options, what it prints */
} rs_command_help;

static const char common_options[] =
    "  --set KEY=VALUE   override a case key by its dotted path, e.g. --set grid.cells=200,\n"
    "                    --set plasticity.k_rel=0.6, --set 'output.fields=[px,pn,regime]';\n"
    "                    sweep lists too: --set 'sweep.rolling.creepage=[-1e-3,-2e-3]',\n"
    "                    --set 'sweep.rolling.creepage={linspace: [0, -0.01, 21]}',\n"
    "                    --set sweep.plasticity.k_rel=null (not swept). The overrides are\n"
    "                    printed under the case's title (which they may make stale).\n"
    "  -h, --help        this help\n";

static const rs_command_help commands[] = {
    {"run",
     "run CASE.yaml [-o OUT.nc] [--set KEY=VALUE]... [--restart OLD.nc [--append]] [--quiet]",
     "solve one case, write its netCDF file, print a summary",
     "Solves the case (simulation.mode: transient from rest or from steady rolling, or\n"
     "steady) and writes the netCDF file given by -o or output.file (its layout:\n"
     "docs/file-format.md); prints F_x/(mu F_n), the cell counts E/H/S/P, solver statistics and\n"
     "the wall time.\n"
     "\n"
     "  -o, --output FILE  the output file (default: output.file of the case, else\n"
     "                     results/CASE.nc). An existing file of that name is kept as FILE~.\n"
     "  --restart OLD.nc   transient: continue from the last record of an earlier run's file\n"
     "                     (its time and state px, upl, ustar; with a prescribed tangential\n"
     "                     force its creepage, with a temperature: block the temperature\n"
     "                     modes) up to the case's end time, on the same output\n"
     "                     times; the new file's history starts with OLD's. Every transient\n"
     "                     file holds that state, whatever output.fields says. Steady: Newton\n"
     "                     starts from that state. Twin-disc runs cannot be restarted (the\n"
     "                     plastic state around the discs is not in the file).\n"
     "  --append           with --restart: continue in OLD.nc itself (records appended, a line\n"
     "                     added to its history, its status updated) instead of a new file.\n"
     "  -q, --quiet        no progress bar (warnings are still printed)\n"
     "\n"
     "Warnings on stderr (the run goes on, the exit code is unchanged): a creepage that looks\n"
     "like a percentage (|xi|, in 3D also |eta|, >= 0.05) or a longitudinal creepage far\n"
     "beyond full sliding (> 10 mu a/R); a transient projected to take more than 2 minutes\n"
     "(ETA and a hint).\n"
     "\n"
     "A case with a profiles: block and vertical_load runs every contact patch at the\n"
     "wheelset's position on its own model into OUT_patchK.nc (one 3D run file per patch);\n"
     "with profiles.lateral_displacement or profiles.yaw a history (transient) the wheelset\n"
     "moves, the contact is updated every output interval and one file over time is\n"
     "written (docs/case-file.md, profiles:).\n"},
    {"check", "check CASE.yaml [--set KEY=VALUE]...",
     "validate a case, print every resolved and derived parameter; run nothing",
     "Validates the case file and prints every key with its resolved value and unit\n"
     "(defaults filled in; the keys of the time axis are left out for steady cases), then\n"
     "derived values: the Hertz half-width a and peak pressure p0, the cell size, the\n"
     "discrete normal solution, the rolled distance of a transient. A case with a sweep:\n"
     "block also gets its swept keys, values, units and number of points. Exit code 2 and\n"
     "a message naming file, line and key for an invalid case; warnings as for run.\n"
     "rollsim check FILE.nc (an output file) is rollsim status FILE.nc.\n"},
    {"sweep", "sweep CASE.yaml [-o OUT.nc] [--set KEY=VALUE]... [--part K/N] [--resume] [--quiet]",
     "run every point of the case's sweep: block into one netCDF file",
     "Runs every combination of the values in the case's sweep: block (dotted keys mapped\n"
     "to lists or {linspace: [from, to, count]}; the last key varies fastest; steady points\n"
     "continue from the previous point along it) and writes one netCDF file with one\n"
     "dimension per swept key (coordinate variables with the key's unit), the scalar\n"
     "results over them and, with output.fields, every point's profiles over (keys..., x)\n"
     "for rollsim_post.py traction/regimes/plastic (output.fields: [] for scalars only).\n"
     "Points go to the file in batches: when a point finishes half a second or more after\n"
     "the last write, and at the end. A killed sweep's file holds every point but those\n"
     "that finished less than half a second after the last write.\n"
     "\n"
     "  -o, --output FILE  the output file (default as for run; an existing one is kept as\n"
     "                     FILE~)\n"
     "  -q, --quiet        no progress line\n"
     "\n"
     "  --part K/N         compute only the K-th of N interleaved shares of the sweep's\n"
     "                     continuation lines (line l when l mod N = K - 1) into its own file\n"
     "                     (the full sweep's shape, other points unwritten); rollsim merge\n"
     "                     joins the parts\n"
     "  --resume           finish the interrupted or killed sweep in OUT.nc (rollsim status\n"
     "                     OUT.nc tells how far it got): the continuation lines complete in\n"
     "                     it are kept, the others computed again from their first point, into\n"
     "                     that file; the numbers are those of a sweep run in one go. The\n"
     "                     same case, --set values and --part as the first run; otherwise\n"
     "                     exit 2 and the file is left untouched\n"
     "\n"
     "Under MPI (mpirun -n N rollsim sweep ...) the continuation lines are farmed out to the\n"
     "ranks (rank 0 computes too and writes the points as they arrive); the file has the\n"
     "serial sweep's numbers plus the per-point variable rank and the attribute ranks.\n"
     "A point that fails is NaN in the file (counts -1, converged 0) and the exit code is 3.\n"
     "\n"
     "On a case with a profiles: block the sweep is a path of wheelset positions: the keys\n"
     "profiles.lateral_displacement, profiles.yaw and profiles.wheel_angular_velocity, lists of\n"
     "one length, the k-th value of each for the k-th position; one file over (position,\n"
     "patch); in one process (no --part, --resume or mpirun).\n"},
    {"fit", "fit CASE.yaml [-o FIT.nc] [--set KEY=VALUE]... [--resume] [--quiet]",
     "fit case keys to measurements (the case's fit: block), write FIT.nc",
     "Fits the parameters of the case's fit: block (case keys with start and bounds) to the\n"
     "measurements of its CSV (input columns: swept case keys such as rolling.creepage, or\n"
     "a twin-disc protocol's step or twin_disc.slip; one measured column; optional\n"
     "weights 1/sigma) by bounded Levenberg-Marquardt (MINPACK). Each evaluation solves\n"
     "the data rows as rollsim sweep would (continuation along the last input column), or\n"
     "the twin-disc protocol once. Prints the stop reason, fitted values with standard\n"
     "errors, the correlation matrix and notes (a parameter at a bound, without effect,\n"
     "correlated pairs). FIT.nc holds parameters, covariance, measured and simulated\n"
     "values; it is rewritten whenever the fit improves, so Ctrl-C keeps the best point\n"
     "(status \"interrupted\", exit code 4). rollsim_post.py fit FIT.nc -o fig.png plots it.\n"
     "\n"
     "  -o, --output FILE  the output file (default: output.file of the case; an existing\n"
     "                     one is kept as FILE~)\n"
     "  --resume           continue the interrupted or killed fit in FILE from its best\n"
     "                     point, counting on its evaluations (same case and --set; a file\n"
     "                     of another case, other --set or data, a truncated or missing\n"
     "                     file: exit 2, the file untouched; a complete fit: nothing to do)\n"
     "  -q, --quiet        no progress line\n"},
    {"merge", "merge OUT.nc PART.nc...",
     "join the parts of a sweep (rollsim sweep --part K/N) into one file",
     "Joins the files of rollsim sweep CASE --part K/N (K = 1..N, e.g. the tasks of a Slurm\n"
     "job array) into OUT.nc, the file the whole sweep writes. Checks that the parts belong\n"
     "to the same case (equal case text) and N, that each is given once and that together\n"
     "they hold every point; otherwise exit 2 naming the files or the missing points, and\n"
     "nothing is written.\n"},
    {"status", "status FILE.nc...", "how far a sweep file got (complete, incomplete, failed)",
     "Prints one line per sweep file: \"complete: M of M points\"; \"incomplete: N of M\n"
     "points (status: ...), last written at DATE\" for a sweep that was interrupted, whose\n"
     "writer was killed (\"running, but its writer, process PID on this host, is gone\") or\n"
     "that is still being written (\"running: process PID on this host is writing it\"):\n"
     "rollsim sweep CASE -o FILE.nc --resume finishes it; \"failed: F of M points did not\n"
     "converge\". A part file (--part K/N) counts the points of its part. Exit 0, or 2 for a\n"
     "file that cannot be read or is truncated.\n"},
    {"help", "help [COMMAND]", "this overview, or the help of one command",
     "Prints the overview of rollsim's commands, or the help of COMMAND (the same as\n"
     "rollsim COMMAND --help).\n"},
};
#define N_COMMANDS (sizeof commands / sizeof commands[0])

static const rs_command_help *find(const char *cmd)
{
  for (size_t i = 0; cmd && i < N_COMMANDS; i++)
    if (!strcmp(commands[i].name, cmd)) return &commands[i];
  return NULL;
}

int rs_cli_is_command(const char *cmd) { return find(cmd) != NULL; }

int rs_cli_help(const char *cmd, FILE *out)
{
  if (!cmd || !*cmd) {
    for (size_t i = 0; i < N_COMMANDS; i++)
      fprintf(out, "%s rollsim %s\n", i ? "      " : "usage:", commands[i].synopsis);
    fprintf(out,
            "       rollsim --help | --version\n\n"
            "Wheel-rail rolling contact with local plasticity, 2D line contact and 3D elliptic\n"
            "point contact (Kalker's theory extended with a yield limit; twin-disc rigs;\n"
            "SUNDIALS IDA/KINSOL, KLU, FFTW, netCDF output).\n\n");
    for (size_t i = 0; i < N_COMMANDS; i++)
      fprintf(out, "  %-6s %s\n", commands[i].name, commands[i].summary);
    fprintf(out, "\n'rollsim COMMAND --help' describes a command and its options. The case file:\n"
                 "docs/case-file.md. Units: mm, N, s, N/mm^2. Exit codes: 0 ok, 2 invalid input\n"
                 "(nothing run, no file written), 3 solver failure (records so far kept),\n"
                 "4 interrupted (records kept), 1 internal or output error.\n");
    return 0;
  }
  const rs_command_help *h = find(cmd);
  if (!h) return -1;
  fprintf(out, "usage: rollsim %s\n\n%s\n%s", h->synopsis, h->summary, h->text);
  if (strcmp(h->name, "help")) fprintf(out, "\nOptions for every command:\n%s", common_options);
  return 0;
}

/* Values of one axis: all of them up to 12, else the first two, the last and the count. */
static void print_values(FILE *out, const rs_sweep_axis *ax)
{
  fputc('[', out);
  if (ax->n <= 12) {
    for (int k = 0; k < ax->n; k++) fprintf(out, "%s%.10g", k ? ", " : "", ax->values[k]);
  } else {
    fprintf(out, "%.10g, %.10g, ..., %.10g", ax->values[0], ax->values[1], ax->values[ax->n - 1]);
  }
  fputc(']', out);
}

void rs_cli_print_sweep(FILE *out, const rs_sweep *s, int dimension)
{
  if (s->positions) {
    fprintf(out, "# sweep on profiles: %zu wheelset positions (the k-th value of every key)\n",
            s->npoints);
    for (int a = 0; a < s->naxes; a++) {
      const rs_sweep_axis *ax = &s->axes[a];
      fprintf(out, "sweep.%s: ", ax->key);
      print_values(out, ax);
      fprintf(out, "  # %s\n", rs_wheel_rail_position_key(ax->key + 9)->unit);
    }
    return;
  }
  fprintf(out, "# sweep: %zu points (", s->npoints);
  for (int a = 0; a < s->naxes; a++) fprintf(out, "%s%d", a ? " x " : "", s->axes[a].n);
  fprintf(out, "; the last key varies fastest)\n");
  for (int a = 0; a < s->naxes; a++) {
    const rs_sweep_axis *ax = &s->axes[a];
    fprintf(out, "sweep.%s: ", ax->key);
    print_values(out, ax);
    const char *unit = rs_case_key_units(ax->key), *note = rs_case_key_unit_note(ax->key);
    if (unit && dimension == 3 && !strcmp(unit, "N/mm")) unit = "N"; /* a total force in 3D */
    fprintf(out, "  # %s%s%s, %d value%s\n",
            *note  ? note
            : unit ? unit
                   : "1",
            "", "", ax->n, ax->n == 1 ? "" : "s");
  }
}
