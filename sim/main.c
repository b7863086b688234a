/* perifem DECK.yaml — the command line, a user of the public C API (include/perifem.h). Exit
 * status: 0 success, 1 run failure, 2 bad input, 128 + N stopped by signal N during the set-up
 * (sim/restart.c). */
#include "include/perifem.h"
#include "sim/sim.h" /* (the library versions, the deck keys, the abort after a failed close) */

#include <errno.h>
#include <exodusII.h>
#include <getopt.h>
#include <hdf5.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#if defined(_OPENMP)
#include <omp.h>
#endif
#include <yaml.h>

static void usage(FILE *fp) {
  fprintf(fp,
          "usage: perifem [options] DECK.yaml   (a value as --opt VALUE or --opt=VALUE)\n"
          "  --check            validate the deck and build the model; print the bodies, step, memory,\n"
          "                     output size, and the run time from a few steps timed here; write\n"
          "                     nothing\n"
          "  --output-dir DIR   write output files into DIR (created when missing)\n"
          "  --restart FILE     continue from the checkpoint FILE (any number of ranks)\n"
          "  --set KEY=VALUE    override a deck value, e.g. for inputs/disk_impact_elastic.yaml\n"
          "                     --set materials.glass.density=2500 or\n"
          "                     --set bodies.sphere.initial_velocity=[0,0,-900] (a list item by its\n"
          "                     index or its name; a YAML value; repeatable; applied after include:\n"
          "                     and before the deck's parameters are substituted)\n"
          "  --quiet            print only errors, the summary's digest line excepted\n"
          "  --strict           a run-health warning (energy error, hourglass, damage jump,\n"
          "                     interpenetration) stops the run as an error (exit status 1)\n"
          "  --progress MODE    auto (one line rewritten in place on a terminal, else plain lines),\n"
          "                     plain or line; under mpirun the ranks see a pseudo-terminal even\n"
          "                     when mpirun's output goes to a file: use plain there\n"
          "  --version          print the version and the libraries it was built with\n"
          "  --deck-keys        print every deck key with its type, default and units (Markdown)\n"
          "  --help, -h         this text\n"
          "exit status: 0 success, 1 run failure, 2 bad input, 128+N stopped by signal N during\n"
          "the set-up\n");
}

static void version(void) {
  unsigned maj, min, rel;
  H5get_libversion(&maj, &min, &rel);
  char mpi[MPI_MAX_LIBRARY_VERSION_STRING];
  int len;
  MPI_Get_library_version(mpi, &len);
  char *nl = strchr(mpi, ',');
  if (nl) *nl = '\0';
  char more[256];
  pf_library_versions(more, sizeof more);
  printf("perifem %s\n  libyaml %s, Exodus II %.2f, HDF5 %u.%u.%u, %s\n  %s\n", perifem_version(),
         yaml_get_version_string(), (double)EX_API_VERS, maj, min, rel, mpi, more);
#if defined(_OPENMP)
  printf("  OpenMP %d: %d threads per rank (OMP_NUM_THREADS; 1 when it is not set)\n", _OPENMP, omp_get_max_threads());
#else
  printf("  no OpenMP threads (the compiler had no OpenMP, or cmake -DPERIFEM_OPENMP=OFF)\n");
#endif
}

enum { MAX_SETS = 256 };

typedef struct {
  const char *deck, *output_dir, *restart;
  int check, quiet, strict, progress;
  const char *sets[MAX_SETS];
  int nsets;
  char command[8192];
} cli;

enum { OPT_CHECK = 256, OPT_OUTPUT_DIR, OPT_RESTART, OPT_SET, OPT_QUIET, OPT_STRICT, OPT_PROGRESS, OPT_VERSION,
       OPT_DECK_KEYS, OPT_HELP = 'h' };

/* Every option, as --name VALUE or --name=VALUE; only --help has a short form (-h). */
static const struct option options[] = {
    {"check", no_argument, NULL, OPT_CHECK},          {"output-dir", required_argument, NULL, OPT_OUTPUT_DIR},
    {"restart", required_argument, NULL, OPT_RESTART}, {"set", required_argument, NULL, OPT_SET},
    {"quiet", no_argument, NULL, OPT_QUIET},          {"strict", no_argument, NULL, OPT_STRICT},
    {"progress", required_argument, NULL, OPT_PROGRESS}, {"version", no_argument, NULL, OPT_VERSION},
    {"deck-keys", no_argument, NULL, OPT_DECK_KEYS},  {"help", no_argument, NULL, OPT_HELP},
    {NULL, 0, NULL, 0}};

/* The option whose name is the token's (its dashes and any "=value" left out), or NULL. */
static const struct option *option_named(const char *token) {
  token += strspn(token, "-");
  const size_t len = strcspn(token, "=");
  for (const struct option *o = options; o->name; o++)
    if (strlen(o->name) == len && !strncmp(o->name, token, len)) return o;
  return NULL;
}

/* An unknown option: say so with the nearest known one (a name it begins, or one a few
 * letters away), then the usage, on stderr. */
static int unknown_option(const char *token) {
  char name[64];
  snprintf(name, sizeof name, "%.*s", (int)strcspn(token + strspn(token, "-"), "="), token + strspn(token, "-"));
  const size_t len = strlen(name);
  const char *best = NULL;
  int bestd = 1 << 30;
  for (const struct option *o = options; o->name; o++) {
    const int d = len && !strncmp(o->name, name, len) ? 0 : pf_edit_distance(name, o->name);
    if (d < bestd) bestd = d, best = o->name;
  }
  if (best && bestd <= 3 && (size_t)bestd < len)
    fprintf(stderr, "perifem error: unknown option '%s' (did you mean --%s?)\n", token, best);
  else fprintf(stderr, "perifem error: unknown option '%s'\n", token);
  usage(stderr);
  return PF_ERR_INPUT;
}

/* What an option with a value needs, for the message when it is missing. */
static int missing_value(int opt) {
  switch (opt) {
  case OPT_SET: fprintf(stderr, "perifem error: --set needs KEY.PATH=VALUE\n"); break;
  case OPT_OUTPUT_DIR: fprintf(stderr, "perifem error: --output-dir needs a directory\n"); break;
  case OPT_RESTART: fprintf(stderr, "perifem error: --restart needs a checkpoint file\n"); break;
  default: fprintf(stderr, "perifem error: --progress needs auto, plain or line (got '')\n"); break;
  }
  return PF_ERR_INPUT;
}

/* Returns -1 to go on, or an exit status. Options and the deck in any order; "--" ends the
 * options. */
static int parse_args(int argc, char **argv, cli *c) {
  opterr = 0; /* (the messages are ours) */
  for (;;) {
    const int at = optind; /* the argument getopt_long reads: "-" keeps them in order */
    int o = getopt_long(argc, argv, "-:h", options, NULL);
    if (o == -1) break;
    const char *token = at < argc ? argv[at] : "";
    if (o == '?' || o == ':') {
      const struct option *known = option_named(token);
      if (!known || strncmp(token, "--", 2)) return unknown_option(token);
      if (o == ':') return missing_value(known->val);
      fprintf(stderr, "perifem error: --%s takes no value (got '%s')\n", known->name, token);
      return PF_ERR_INPUT;
    }
    if (o != 1 && token[0] == '-' && token[1] == '-' && !option_named(token)) return unknown_option(token);
    if (o == 1 && c->deck) {
      fprintf(stderr, "perifem error: more than one deck given ('%s' and '%s')\n", c->deck, optarg);
      return PF_ERR_INPUT;
    }
    if ((o == OPT_SET || o == OPT_OUTPUT_DIR || o == OPT_RESTART) && !*optarg) return missing_value(o);
    switch (o) {
    case 1: c->deck = optarg; break;
    case OPT_HELP: return usage(stdout), 0;
    case OPT_VERSION: return version(), 0;
    case OPT_DECK_KEYS: return pf_deck_reference(stdout);
    case OPT_CHECK: c->check = 1; break;
    case OPT_QUIET: c->quiet = 1; break;
    case OPT_STRICT: c->strict = 1; break;
    case OPT_PROGRESS:
      if (strcmp(optarg, "auto") && strcmp(optarg, "plain") && strcmp(optarg, "line")) {
        fprintf(stderr, "perifem error: --progress needs auto, plain or line (got '%s')\n", optarg);
        return PF_ERR_INPUT;
      }
      c->progress = !strcmp(optarg, "auto") ? 0 : !strcmp(optarg, "plain") ? 1 : 2;
      break;
    case OPT_SET:
      if (c->nsets == MAX_SETS) {
        fprintf(stderr, "perifem error: --set: at most %d overrides\n", MAX_SETS);
        return PF_ERR_INPUT;
      }
      c->sets[c->nsets++] = optarg;
      break;
    case OPT_OUTPUT_DIR: c->output_dir = optarg; break;
    case OPT_RESTART: c->restart = optarg; break;
    default: return unknown_option(token);
    }
  }
  for (int i = optind; i < argc; i++) { /* (after "--") */
    if (c->deck) {
      fprintf(stderr, "perifem error: more than one deck given ('%s' and '%s')\n", c->deck, argv[i]);
      return PF_ERR_INPUT;
    }
    c->deck = argv[i];
  }
  if (!c->deck) {
    usage(stderr);
    return PF_ERR_INPUT;
  }
  return -1;
}

/* The command line as a shell would take it back (arguments with other than plain characters
 * in single quotes), for the outputs' provenance. */
static void command_line(int argc, char **argv, char *out, size_t len) {
  size_t at = 0;
  out[0] = '\0';
  for (int i = 0; i < argc && at < len; i++) {
    const int plain = argv[i][0] && strspn(argv[i], "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                   "0123456789_-+=.,/:@%") == strlen(argv[i]);
    at += (size_t)snprintf(out + at, len - at, plain ? "%s%s" : "%s'%s'", i ? " " : "", argv[i]);
  }
}

static int exit_status(int ierr) { return ierr ? (ierr == PERIFEM_ERR_INPUT ? 2 : 1) : 0; }

static int run(const cli *c) {
  const perifem_options opt = {.overrides = c->sets, .noverrides = c->nsets, .output_dir = c->output_dir,
                               .restart_from = c->restart, .quiet = c->quiet, .strict = c->strict,
                               .progress = c->progress, .catch_signals = 1, .command_line = c->command};
  perifem_sim *sim = NULL;
  int ierr = perifem_create(c->deck, &opt, &sim);
  if (ierr) return exit_status(ierr);
  if (c->check) {
    ierr = perifem_print_check(sim);
    perifem_destroy(&sim);
    return ierr ? 1 : 0;
  }
  const int err = c->output_dir ? pf_sim_make_dir(c->output_dir) : 0;
  if (err) {
    if (pf_comm_rank() == 0)
      fprintf(stderr, "perifem error: --output-dir %s: cannot create the folder: %s\n", c->output_dir, strerror(err));
    perifem_destroy(&sim);
    return 2;
  }
  ierr = perifem_run(sim);
  uint64_t digest;
  if (!ierr && perifem_finished(sim)) { /* (not after a signal stopped the run) */
    ierr = perifem_digest(sim, &digest);
    if (!ierr && pf_comm_rank() == 0) printf("state digest: %016" PRIx64 "\n", digest); /* even with --quiet */
  }
  perifem_destroy(&sim);
  return exit_status(ierr);
}

/* One thread per rank unless OMP_NUM_THREADS says otherwise: an MPI launch of one rank per core
 * then never runs ranks x cores threads on the cores (docs/user_guide.md, "Threads"). */
static void default_threads(void) {
#if defined(_OPENMP)
  const char *n = getenv("OMP_NUM_THREADS");
  if (!n || !*n) omp_set_num_threads(1);
#endif
}

int main(int argc, char **argv) {
  default_threads();
  /* A write past the file-size limit (ulimit -f) fails with EFBIG, like one on a full disk
   * fails with ENOSPC, and ends the run with a message instead of killing the process. */
  signal(SIGXFSZ, SIG_IGN);
  pf_sim_catch_signals_early(); /* (MPI_Init takes a second or more: a signal then had no message) */
  pf_mpi_defaults();
  MPI_Init(&argc, &argv);
  pf_mpi_defaults_release();
  static cli c; /* (large: not on the stack) */
  command_line(argc, argv, c.command, sizeof c.command);
  int status = parse_args(argc, argv, &c);
  if (status < 0) {
    pf_log_set_quiet(c.quiet);
    status = run(&c);
  }
  /* (a file HDF5 could not write is left open: MPI_Finalize would make HDF5 close it, and crash) */
  if (status && (pf_comm_size() > 1 || pf_io_abandoned())) MPI_Abort(MPI_COMM_WORLD, status);
  MPI_Finalize();
  return status;
}
