/* The command-line program, run as a user would: every error path exits
 * with status 2, prints one message naming the problem and writes no file;
 * the success paths write the image and the summary line. */
/* sched_setaffinity, to run glint on one CPU */
#define _GNU_SOURCE
#include "test_util.h"

#include <dirent.h>
#include <sched.h>
#include <signal.h>

#include <fcntl.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

static char dir[64];
static char out[65536], err[65536];
static const char *extra_env; /* one more NAME=value (or one in its
                                  place) for the next run */

static int setup(void **state) {
  (void)state;
  strcpy(dir, "/tmp/glint-test-cli-XXXXXX");
  return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  return system(cmd) == 0 ? 0 : -1;
}

static void slurp(const char *path, char *buf, size_t size) {
  FILE *f = fopen(path, "rb");
  size_t n = f ? fread(buf, 1, size - 1, f) : 0;
  buf[n] = '\0';
  if (f)
    fclose(f);
}

/* Runs glint with the given arguments (NULL-terminated) in the test folder;
 * returns the exit status and fills out/err. */
/* Starts glint with argv and envp, its standard output to out_path
 * (opened to write; created when missing) and standard error to err_path
 * (created or emptied), either closed where NULL; returns its pid. */
static pid_t spawn_glint(char *const argv[], char *const envp[],
                         const char *out_path, const char *err_path) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  if (out_path)
    posix_spawn_file_actions_addopen(&fa, 1, out_path, O_WRONLY | O_CREAT,
                                     0644);
  else
    posix_spawn_file_actions_addclose(&fa, 1);
  if (err_path)
    posix_spawn_file_actions_addopen(&fa, 2, err_path,
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  else
    posix_spawn_file_actions_addclose(&fa, 2);
  pid_t pid;
  int rc = posix_spawn(&pid, GLINT_EXE, &fa, NULL, argv, envp);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0)
    fail_msg("cannot run %s", GLINT_EXE);
  return pid;
}

/* Waits for glint (pid) to end, puts what it wrote to err_path in err (and
 * removes the file), and returns its exit status; a glint killed by a
 * signal fails the test. */
static int exit_status(pid_t pid, const char *err_path) {
  int status;
  assert_int_equal(waitpid(pid, &status, 0), pid);
  slurp(err_path, err, sizeof err);
  unlink(err_path);
  if (!WIFEXITED(status))
    fail_msg("glint was killed by signal %d; stderr: %s", WTERMSIG(status),
             err);
  return WEXITSTATUS(status);
}

static int run(const char *first, ...) {
  const char *argv[64] = {GLINT_EXE};
  int n = 1;
  va_list ap;
  va_start(ap, first);
  for (const char *a = first; a && n < 63; a = va_arg(ap, const char *))
    argv[n++] = a;
  va_end(ap);
  argv[n] = NULL;
  char out_path[128], err_path[128];
  snprintf(out_path, sizeof out_path, "%s/.stdout", dir);
  snprintf(err_path, sizeof err_path, "%s/.stderr", dir);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, out_path,
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, err_path,
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  char cwd[512];
  if (!getcwd(cwd, sizeof cwd) || chdir(dir) != 0)
    fail_msg("cannot enter %s", dir);
  const char *envp[512];
  int ne = 0;
  size_t replaced = extra_env ? strcspn(extra_env, "=") + 1 : 0;
  for (char **e = environ; *e && ne < 510; e++)
    if (!extra_env || strncmp(*e, extra_env, replaced) != 0)
      envp[ne++] = *e;
  if (extra_env)
    envp[ne++] = extra_env;
  envp[ne] = NULL;
  pid_t pid;
  int rc = posix_spawn(&pid, GLINT_EXE, &fa, NULL, (char *const *)argv,
                       (char *const *)envp);
  if (chdir(cwd) != 0)
    fail_msg("cannot return to %s", cwd);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0)
    fail_msg("cannot run %s", GLINT_EXE);
  int status;
  waitpid(pid, &status, 0);
  slurp(out_path, out, sizeof out);
  slurp(err_path, err, sizeof err);
  unlink(out_path);
  unlink(err_path);
  if (!WIFEXITED(status))
    fail_msg("glint did not exit normally (signal %d); stderr: %s",
             WIFSIGNALED(status) ? WTERMSIG(status) : 0, err);
  return WEXITSTATUS(status);
}

static int exists(const char *name) {
  char p[512];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  struct stat sb;
  return stat(p, &sb) == 0;
}

/* Removes the file or empty folder NAME of the test folder; 0 when done. */
static int remove_in_folder(const char *name) {
  char p[512];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  return remove(p);
}

/* Writes `text` to NAME in the test folder. */
static void put_text(const char *name, const char *text) {
  char p[256];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  FILE *f = fopen(p, "wb");
  fputs(text, f);
  fclose(f);
}

/* A sphere in front of the camera, 8x8: the smallest scene file a test
 * needs to be there (the start "v\nfrom" tells that it was kept). */
static const char small_nff[] = "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 40\n"
                                "hither 0.001\nresolution 8 8\n"
                                "f 1 1 1 1 0 0 0 1\ns 0 0 0 1\n";

/* Only the stdout/stderr capture files may be in the folder. */
static int folder_is_empty(void) {
  char cmd[256];
  snprintf(cmd, sizeof cmd, "test -z \"$(ls -A '%s')\"", dir);
  return system(cmd) == 0;
}

/* Exit status 2 and `text` in stderr, the test's own files left alone. */
#define EXPECT_USAGE_ERROR_KEEPING(text, ...)                                  \
  do {                                                                         \
    int rc_ = run(__VA_ARGS__, NULL);                                          \
    if (rc_ != 2)                                                              \
      fail_msg("exit %d, want 2; stderr: %s", rc_, err);                       \
    if (!strstr(err, text))                                                    \
      fail_msg("stderr '%s' lacks '%s'", err, text);                           \
  } while (0)

/* The same, as one line starting "glint: ", and nothing written. */
#define EXPECT_USAGE_ERROR(text, ...)                                          \
  do {                                                                         \
    EXPECT_USAGE_ERROR_KEEPING(text, __VA_ARGS__);                             \
    if (strncmp(err, "glint: ", 7) != 0 ||                                     \
        strchr(err, '\n') != err + strlen(err) - 1)                            \
      fail_msg("want exactly one line starting 'glint: ', got '%s'", err);     \
    if (!folder_is_empty())                                                    \
      fail_msg("a file was written on error");                                 \
  } while (0)

static void usage_errors(void **state) {
  (void)state;
  EXPECT_USAGE_ERROR("unknown command 'paint'", "paint");
  EXPECT_USAGE_ERROR("unknown scene 'cornell'", "render", "cornell");
  EXPECT_USAGE_ERROR("-: a scene is a file (.nff or .json, optionally .gz) or "
                     "a built-in scene's name, not standard input",
                     "render", "-");
  EXPECT_USAGE_ERROR("unknown backend 'gpu'", "render", "-b", "gpu");
  /* What a message quotes reaches the terminal without its control
   * characters (an escape sequence is a terminal command). */
  EXPECT_USAGE_ERROR("unknown backend 'gpu?[31m'", "render", "-b",
                     "gpu\033[31m");
  EXPECT_USAGE_ERROR("unknown option '--fast'", "render", "--fast");
  /* A flag with a value is refused (it was taken as the flag: --quiet=no
   * ran quiet, --no-newton=0 dropped the Newton step, -hello was help). */
  EXPECT_USAGE_ERROR("--quiet takes no value: '--quiet=no'", "render",
                     "--quiet=no");
  EXPECT_USAGE_ERROR("--quiet takes no value: '-qfoo'", "render", "-qfoo");
  EXPECT_USAGE_ERROR("--no-newton takes no value", "render", "--no-newton=0");
  EXPECT_USAGE_ERROR("--time-to-image takes no value", "bench",
                     "--time-to-image=1");
  EXPECT_USAGE_ERROR("unknown option '-hello'", "render", "-hello");
  /* --help with a value is named as such (it was "unknown option") */
  EXPECT_USAGE_ERROR("--help takes no value: '--help=1'", "compare",
                     "--help=1");
  EXPECT_USAGE_ERROR("--help takes no value: '-h=1'", "render", "-h=1");
  EXPECT_USAGE_ERROR("--help takes no value", "bench", "--help=yes");
  EXPECT_USAGE_ERROR("--help takes no value: '--help=1'", "--help=1");
  /* compare takes "--" as render does: images after it (it said "unknown
   * option '--'") */
  EXPECT_USAGE_ERROR("-x.png", "compare", "--", "-x.png", "-y.png");
  EXPECT_USAGE_ERROR("more than one scene", "render", "whitted", "giza");
  /* A file with no extension is read as the file it is, and refused as no
   * scene file (it was "unknown scene 'bare'", as if it were not there) */
  char bare[600];
  snprintf(bare, sizeof bare, "%s/bare", dir);
  FILE *bare_file = fopen(bare, "w");
  assert_non_null(bare_file);
  fputs("s 0 0 0 1\n", bare_file);
  assert_int_equal(fclose(bare_file), 0);
  EXPECT_USAGE_ERROR_KEEPING("glint: bare: not a scene file (.nff or .json",
                             "render", "bare");
  EXPECT_USAGE_ERROR_KEEPING("glint: bare: not a scene file", "view", "bare");
  assert_int_equal(unlink(bare), 0);
  EXPECT_USAGE_ERROR("--output needs a value", "render", "-o");
  EXPECT_USAGE_ERROR("--math", "render", "--math", "sloppy");
  EXPECT_USAGE_ERROR("--accel", "render", "--accel", "kdtree");
  EXPECT_USAGE_ERROR("--gamma: 0 is outside 0.01..100", "render", "--gamma",
                     "0");
  EXPECT_USAGE_ERROR("--gamma: ' 2' is not a number", "render", "--gamma",
                     " 2");
  EXPECT_USAGE_ERROR("--gamma: '0x2' is not a number", "render", "--gamma",
                     "0x2");
  EXPECT_USAGE_ERROR("--gamma: 1e308 is outside 0.01..100", "render", "--gamma",
                     "1e308");
  EXPECT_USAGE_ERROR("--gamma: 1e-308 is outside 0.01..100", "view", "--gamma",
                     "1e-308");
  /* what was typed, not what it reads as (0) */
  EXPECT_USAGE_ERROR("--gamma: 1e-400 is outside 0.01..100", "render",
                     "--gamma", "1e-400");
  EXPECT_USAGE_ERROR("--png-compression applies to PNG images, and x.ppm is "
                     "not one",
                     "render", "--png-compression", "smallest", "-o", "x.ppm");
  EXPECT_USAGE_ERROR("--png-compression applies to PNG images, and the stream",
                     "render", "--png-compression", "fast", "-o", "-",
                     "--format", "bmp");
}

static void size_errors(void **state) {
  (void)state;
  EXPECT_USAGE_ERROR("--width: 0 is outside 1..16384", "render", "-W", "0");
  EXPECT_USAGE_ERROR("--width: -5 is outside", "render", "-W", "-5");
  EXPECT_USAGE_ERROR("--height: 0 is outside", "render", "--height=0");
  EXPECT_USAGE_ERROR("--width: 'abc' is not a whole number", "render", "-W",
                     "abc");
  EXPECT_USAGE_ERROR("--width: '64x' is not a whole number", "render", "-W64x");
  EXPECT_USAGE_ERROR("--width: ' 64' is not a whole number", "render", "-W",
                     " 64");
  EXPECT_USAGE_ERROR("--height: 100000 is outside", "render", "-H", "100000");
  EXPECT_USAGE_ERROR("--width: 99999999999999999999 is outside 1..16384",
                     "render", "-W", "99999999999999999999");
  EXPECT_USAGE_ERROR("--depth: 0 is outside 1..64", "render", "-d", "0");
  EXPECT_USAGE_ERROR("--depth: 65 is outside 1..64", "render", "-d", "65");
  EXPECT_USAGE_ERROR("--spp: 0 is outside 1..4096", "render", "-s", "0");
  EXPECT_USAGE_ERROR("--threads: -1 is outside", "render", "-t", "-1");
  /* --region: four plain numbers, none wrapping past 2^32 into a small one */
  EXPECT_USAGE_ERROR("--region: '4294967311,4294967311,1,1' is not "
                     "X,Y,WIDTH,HEIGHT",
                     "render", "--region", "4294967311,4294967311,1,1");
  EXPECT_USAGE_ERROR("--region: '0,0,4294967297,1'", "render", "--region",
                     "0,0,4294967297,1");
  EXPECT_USAGE_ERROR("--region: '0,0,0,1'", "render", "--region", "0,0,0,1");
  EXPECT_USAGE_ERROR("--region: '1,1,1'", "render", "--region", "1,1,1");
  EXPECT_USAGE_ERROR("--region: '1,1,1,1,1'", "render", "--region",
                     "1,1,1,1,1");
  EXPECT_USAGE_ERROR("--region: ' 1,1,1,1'", "render", "--region", " 1,1,1,1");
  EXPECT_USAGE_ERROR("--region: '-1,0,1,1'", "render", "--region", "-1,0,1,1");
  EXPECT_USAGE_ERROR("--region: '16385,0,1,1'", "render", "--region",
                     "16385,0,1,1");
  EXPECT_USAGE_ERROR("--region: '++1,0,1,1'", "render", "--region",
                     "++1,0,1,1");
  EXPECT_USAGE_ERROR("--region: '+,0,1,1'", "render", "--region", "+,0,1,1");
}

static void output_errors(void **state) {
  (void)state;
  EXPECT_USAGE_ERROR("out.jpg: unknown output format (use .png, .bmp or .ppm, "
                     "or .pfm or .exr for the linear film)",
                     "render", "-W", "8", "-H", "8", "-o", "out.jpg");
  EXPECT_USAGE_ERROR("unknown output format", "render", "-W", "8", "-H", "8",
                     "-o", "out");
  EXPECT_USAGE_ERROR("the output file name is empty", "render", "-W", "8", "-H",
                     "8", "-o", "");
  EXPECT_USAGE_ERROR("/no/such/folder/out.png: cannot write here", "render",
                     "-W", "8", "-H", "8", "-o", "/no/such/folder/out.png");
  char sub[128];
  snprintf(sub, sizeof sub, "%s/sub.png", dir);
  mkdir(sub, 0755);
  int rc = run("render", "-W", "8", "-H", "8", "-o", "sub.png", NULL);
  assert_int_equal(rc, 2);
  assert_non_null(strstr(err, "is a directory"));
  rmdir(sub);
  /* Names up to NAME_MAX (255 bytes) are written, though the temporary
   * name beside them, ".NAME.XXXXXX", would be longer; longer names are
   * refused before rendering. */
  char name[300];
  memset(name, 'a', 251);
  strcpy(name + 251, ".png");
  assert_int_equal(run("render", "-W", "8", "-H", "8", "-q", "-o", name, NULL),
                   0);
  assert_true(exists(name));
  remove_in_folder(name);
  memset(name, 'a', 252);
  strcpy(name + 252, ".png");
  EXPECT_USAGE_ERROR("cannot write here: File name too long", "render", "-W",
                     "8", "-H", "8", "-o", name);
}

/* An existing image survives a failed run untouched. */
static void existing_file_survives_errors(void **state) {
  (void)state;
  char p[128];
  snprintf(p, sizeof p, "%s/keep.png", dir);
  FILE *f = fopen(p, "wb");
  fputs("precious", f);
  fclose(f);
  assert_int_equal(run("render", "-d", "99", "-o", "keep.png", NULL), 2);
  assert_int_equal(run("render", "nosuchscene", "-o", "keep.png", NULL), 2);
  /* Writing fails while the frame renders (the image is encoded as its
   * tiles arrive): here the file-size limit, as a full disk would. */
  struct rlimit saved, small;
  getrlimit(RLIMIT_FSIZE, &saved);
  small = saved;
  small.rlim_cur = 20000; /* the .stdout/.stderr captures fit; the PNG not */
  signal(SIGXFSZ, SIG_IGN);
  setrlimit(RLIMIT_FSIZE, &small);
  int rc = run("render", "whitted", "-t", "1", "-o", "keep.png", NULL);
  int png_said = strstr(err, "keep.png: writing failed: File too large") != 0;
  /* the film as OpenEXR says why as well (it said "encoder error") */
  int rc_exr = run("render", "whitted", "-t", "1", "-o", "film.exr", NULL);
  setrlimit(RLIMIT_FSIZE, &saved);
  signal(SIGXFSZ, SIG_DFL);
  assert_int_equal(rc, 2);
  assert_true(png_said);
  assert_int_equal(rc_exr, 2);
  assert_non_null(strstr(err, "film.exr: writing failed: File too large"));
  assert_false(exists("film.exr"));
  char buf[32];
  slurp(p, buf, sizeof buf);
  assert_string_equal(buf, "precious");
  unlink(p);
  assert_true(folder_is_empty());
}

static void help_and_version(void **state) {
  (void)state;
  assert_int_equal(run("--version", NULL), 0);
  assert_non_null(strstr(out, "glint 0."));
  assert_int_equal(run("--help", NULL), 0);
  assert_non_null(strstr(out, "glint render"));
  assert_int_equal(run("help", "bench", NULL), 0);
  assert_non_null(strstr(out, "--backends"));
  assert_int_equal(run("help", "render", "extra", NULL), 2);
  assert_non_null(strstr(err, "help takes one command: 'extra' follows "
                              "'render'"));
  assert_int_equal(run("help", "paint", NULL), 2);
  assert_non_null(strstr(err, "help: unknown command 'paint'"));
  assert_int_equal(run("--version", "extra", NULL), 2);
  assert_non_null(strstr(err, "--version takes nothing after it: 'extra'"));
  assert_int_equal(run("--help", "render", "x", NULL), 2);
  assert_non_null(strstr(err, "glint COMMAND --help"));
  assert_int_equal(run("render", "--help", NULL), 0);
  assert_non_null(strstr(out, "--backend"));
  assert_non_null(strstr(out, "--depth"));
  assert_int_equal(run("bench", "--help", NULL), 0);
  assert_non_null(strstr(out, "--runs"));
  assert_int_equal(run(NULL), 2); /* no command: usage on stderr */
  assert_non_null(strstr(err, "Usage"));
  /* glint view's help and option errors come from glint, also where the
   * window program glint-view is not beside it (they said it was missing) */
  char alone[700], cmd[2400];
  snprintf(alone, sizeof alone, "%s/alone", dir);
  snprintf(cmd, sizeof cmd, "mkdir '%s' && cp '%s' '%s/glint'", alone,
           GLINT_EXE, alone);
  assert_int_equal(system(cmd), 0);
  snprintf(
      cmd, sizeof cmd,
      "'%s/glint' help view | grep -q '^Usage: glint view' && "
      "'%s/glint' view --help | grep -q '^Usage: glint view' && "
      "'%s/glint' view --bogus 2>&1 | grep -q \"unknown option '--bogus'\"",
      alone, alone, alone);
  assert_int_equal(system(cmd), 0);
  snprintf(cmd, sizeof cmd, "rm -r '%s'", alone);
  assert_int_equal(system(cmd), 0);
}

static void render_writes_every_format(void **state) {
  (void)state;
  const char *names[] = {"w.png", "w.bmp", "w.ppm"};
  for (int i = 0; i < 3; i++) {
    assert_int_equal(
        run("render", "whitted", "-W", "32", "-H", "24", "-o", names[i], NULL),
        0);
    assert_true(exists(names[i]));
    /* The summary line: wall time, rays by kind and the rate. */
    assert_non_null(strstr(out, names[i]));
    assert_non_null(strstr(out, " s, "));
    assert_non_null(strstr(out, "primary"));
    assert_non_null(strstr(out, "secondary"));
    assert_non_null(strstr(out, "shadow"));
    assert_non_null(strstr(out, "Mrays/s"));
    assert_string_equal(err, ""); /* no progress bar when not a terminal */
  }
  glint_image *a, *b;
  char pa[128], pb[128];
  snprintf(pa, sizeof pa, "%s/w.png", dir);
  snprintf(pb, sizeof pb, "%s/w.bmp", dir);
  ASSERT_OK(glint_image_read(pa, &a, &e_));
  ASSERT_OK(glint_image_read(pb, &b, &e_));
  assert_int_equal(glint_image_width(a), 32);
  assert_memory_equal(glint_image_pixels_const(a), glint_image_pixels_const(b),
                      32 * 24 * 3);
  glint_image_destroy(a);
  glint_image_destroy(b);
  char cmd[256];
  snprintf(cmd, sizeof cmd, "rm -f '%s'/w.*", dir);
  assert_int_equal(system(cmd), 0);
}

/* The linear film as .pfm: the same pixels as the 8-bit image, before the
 * conversion; --gamma is refused for it, and an unwritable place is caught
 * before rendering. (.exr is read back in test_film.) */
static void render_writes_the_film(void **state) {
  (void)state;
  assert_int_equal(
      run("render", "whitted", "-W", "32", "-H", "24", "-o", "w.pfm", NULL), 0);
  assert_int_equal(
      run("render", "whitted", "-W", "32", "-H", "24", "-o", "w.ppm", NULL), 0);
  char pf[128], pp[128];
  snprintf(pf, sizeof pf, "%s/w.pfm", dir);
  snprintf(pp, sizeof pp, "%s/w.ppm", dir);
  glint_image *im;
  ASSERT_OK(glint_image_read(pp, &im, &e_));
  FILE *f = fopen(pf, "rb");
  assert_non_null(f);
  char header[32];
  assert_non_null(fgets(header, sizeof header, f));
  assert_string_equal(header, "PF\n");
  assert_non_null(fgets(header, sizeof header, f));
  assert_string_equal(header, "32 24\n");
  assert_non_null(fgets(header, sizeof header, f));
  const uint8_t *bytes = glint_image_pixels_const(im);
  for (int y = 23; y >= 0; y--)
    for (int i = 0; i < 32 * 3; i++) {
      float v;
      assert_int_equal(fread(&v, 4, 1, f), 1);
      assert_int_equal(bytes[y * 32 * 3 + i], expected_byte(v));
    }
  fclose(f);
  glint_image_destroy(im);
  unlink(pf);
  unlink(pp);
  EXPECT_USAGE_ERROR("--gamma applies to 8-bit images", "render", "-W", "8",
                     "-H", "8", "--gamma", "2.2", "-o", "out.pfm");
  EXPECT_USAGE_ERROR("/no/such/folder/out.exr: cannot write here", "render",
                     "-W", "8", "-H", "8", "-o", "/no/such/folder/out.exr");
}

/* The 4-byte big-endian value of a PNG's gAMA chunk, or 0. */
static unsigned png_gamma(const char *name) {
  char p[256];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  FILE *f = fopen(p, "rb");
  assert_non_null(f);
  unsigned char buf[4096];
  size_t n = fread(buf, 1, sizeof buf, f);
  fclose(f);
  for (size_t i = 0; i + 8 <= n; i++)
    if (memcmp(buf + i, "gAMA", 4) == 0)
      return (unsigned)buf[i + 4] << 24 | (unsigned)buf[i + 5] << 16 |
             (unsigned)buf[i + 6] << 8 | buf[i + 7];
  return 0;
}

static long file_size(const char *name) {
  char p[256];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  struct stat sb;
  return stat(p, &sb) == 0 ? (long)sb.st_size : -1;
}

/* PNG options: the same pixels fast or smallest, the gamma recorded. */
static void png_compression_and_gamma(void **state) {
  (void)state;
  assert_int_equal(
      run("render", "-W", "64", "-H", "48", "-o", "fast.png", NULL), 0);
  assert_int_equal(run("render", "-W", "64", "-H", "48", "--png-compression",
                       "smallest", "--gamma", "2.2", "-o", "small.png", NULL),
                   0);
  assert_int_equal(run("render", "-W", "64", "-H", "48", "--gamma", "2.2", "-o",
                       "fast22.png", NULL),
                   0);
  assert_true(file_size("small.png") < file_size("fast22.png"));
  assert_int_equal(png_gamma("fast.png"), 100000); /* linear */
  assert_int_equal(png_gamma("small.png"), 45455); /* 1/2.2 */
  glint_image *a, *b;
  char pa[256], pb[256];
  snprintf(pa, sizeof pa, "%s/small.png", dir);
  snprintf(pb, sizeof pb, "%s/fast22.png", dir);
  ASSERT_OK(glint_image_read(pa, &a, &e_));
  ASSERT_OK(glint_image_read(pb, &b, &e_));
  assert_memory_equal(glint_image_pixels_const(a), glint_image_pixels_const(b),
                      64 * 48 * 3);
  glint_image_destroy(a);
  glint_image_destroy(b);
  unlink(pa);
  unlink(pb);
  snprintf(pa, sizeof pa, "%s/fast.png", dir);
  unlink(pa);
  EXPECT_USAGE_ERROR("--png-compression: 'best' is not fast or smallest",
                     "render", "--png-compression", "best", "-o", "x.png");
}

static void defaults_quiet_and_stats(void **state) {
  (void)state;
  /* The default output is SCENE.png. */
  assert_int_equal(run("render", "phong", "-W", "16", "-H", "12", "-q", NULL),
                   0);
  assert_true(exists("phong.png"));
  assert_string_equal(out, "");
  assert_string_equal(err, "");
  assert_int_equal(run("render", "phong", "-W", "16", "-H", "12", "--stats",
                       "-b", "scalar-float", NULL),
                   0);
  assert_non_null(strstr(out, "reflected"));
  assert_non_null(strstr(out, "peak memory"));
  assert_non_null(strstr(out, "scalar-float"));
  char p[128];
  snprintf(p, sizeof p, "%s/phong.png", dir);
  unlink(p);
}

static void bench_runs_and_writes_csv(void **state) {
  (void)state;
  assert_int_equal(run("bench", "--scenes", "whitted,phong", "--depths", "1,2",
                       "--runs", "1", "-W", "16", "-H", "12", "-s", "1",
                       "--backends", "scalar-float,scalar-double", "--csv",
                       "b.csv", NULL),
                   0);
  assert_non_null(strstr(out, "Scene \"whitted\": seconds"));
  assert_non_null(strstr(out, "Scene \"phong\": Mrays/s"));
  assert_non_null(strstr(out, "scalar-double"));
  char p[128], csv[4096];
  snprintf(p, sizeof p, "%s/b.csv", dir);
  slurp(p, csv, sizeof csv);
  int lines = 0;
  for (char *c = csv; *c; c++)
    lines += *c == '\n';
  assert_int_equal(lines, 1 + 2 * 2 * 2);
  assert_non_null(strstr(csv, "scene,depth,backend"));
  assert_non_null(strstr(csv, "phong,2,scalar-float,16,12,1,1,1,"));
  unlink(p);
}

/* The CSV row of `scene,depth,backend,` in csv, from its rays on (the
 * timings before them differ from run to run). */
static const char *csv_rays(const char *csv, const char *row) {
  const char *p = strstr(csv, row);
  assert_non_null(p);
  for (int field = 0; field < 11; field++) {
    p = strchr(p, ',');
    assert_non_null(p);
    p++;
  }
  return p;
}

/* A column keeps one renderer across the table's depths and runs: a depth
 * rendered after a deeper one counts the rays, lanes and generations that
 * a table of it alone counts (the renderer is made for the deepest, and its
 * stream buffers hold the deeper generations' rays). */
static void bench_reuses_a_renderer_per_column(void **state) {
  (void)state;
  const char *backends = glint_backend_supported(GLINT_BACKEND_STREAM_SSE)
                             ? "scalar-float,stream-sse"
                             : "scalar-float";
  char p[128], alone[8192], after[8192];
  snprintf(p, sizeof p, "%s/b.csv", dir);
  assert_int_equal(run("bench", "--scenes", "billiard", "--depths", "2",
                       "--runs", "1", "-W", "24", "-H", "16", "-s", "2",
                       "--backends", backends, "--csv", "b.csv", NULL),
                   0);
  slurp(p, alone, sizeof alone);
  assert_int_equal(run("bench", "--scenes", "billiard", "--depths", "9,2",
                       "--runs", "2", "-W", "24", "-H", "16", "-s", "2",
                       "--backends", backends, "--csv", "b.csv", NULL),
                   0);
  slurp(p, after, sizeof after);
  unlink(p);
  const char *rows[] = {"billiard,2,scalar-float,", "billiard,2,stream-sse,"};
  for (int k = 0; k < (strchr(backends, 'm') ? 2 : 1); k++) {
    const char *a = csv_rays(alone, rows[k]), *b = csv_rays(after, rows[k]);
    /* rays, primary, secondary and shadow rays: four fields */
    const char *end = a;
    for (int field = 0; field < 4; field++)
      end = strchr(end, ',') + 1;
    assert_memory_equal(a, b, (size_t)(end - a));
    assert_int_not_equal(
        strncmp(b,
                csv_rays(after, k ? "billiard,9,stream-sse,"
                                  : "billiard,9,scalar-float,"),
                (size_t)(end - a)),
        0);
  }
}

/* An auto column renders each scene and depth with what glint render
 * chooses for them (the streams for Billiard at depth 15 where the CPU has
 * them, the beams at depth 1), and its CSV rows name that backend. It was
 * resolved once, without a scene: the widest beams at every depth. */
static void bench_auto_renders_what_render_chooses(void **state) {
  (void)state;
  char p[128], csv[4096];
  snprintf(p, sizeof p, "%s/b.csv", dir);
  assert_int_equal(run("bench", "--scenes", "billiard", "--depths", "1,15",
                       "--runs", "1", "-W", "24", "-H", "16", "-s", "1",
                       "--backends", "auto", "--csv", "b.csv", NULL),
                   0);
  assert_non_null(strstr(out, "           auto\n"));
  slurp(p, csv, sizeof csv);
  unlink(p);
  /* the header names a last field, the column asked for */
  assert_non_null(strstr(csv, ",generation_lane_use,column\n"));
  const char *depths[] = {"1", "15"};
  for (int k = 0; k < 2; k++) {
    snprintf(p, sizeof p, "%s/a.ppm", dir);
    assert_int_equal(run("render", "billiard", "-d", depths[k], "-W", "24",
                         "-H", "16", "-s", "1", "-t", "1", "--stats", "-o",
                         "a.ppm", NULL),
                     0);
    unlink(p);
    const char *b = strstr(out, "backend            ");
    assert_non_null(b);
    b += strlen("backend            ");
    char row[64];
    int n = (int)strcspn(b, ",");
    snprintf(row, sizeof row, "billiard,%s,%.*s,", depths[k], n, b);
    const char *line = strstr(csv, row);
    assert_non_null(line);
    const char *end = strchr(line, '\n');
    assert_non_null(end);
    assert_true(end - line > 5 && strncmp(end - 5, ",auto", 5) == 0);
  }
}

/* --time-to-image: glint render as a child process, PNG and PPM, against
 * the render; its images go to a folder of its own that it removes. */
static void bench_time_to_image(void **state) {
  (void)state;
  assert_int_equal(run("bench", "--time-to-image", "--scenes", "whitted,phong",
                       "--runs", "1", "-W", "16", "-H", "12", "-s", "1",
                       "--backends", "scalar-float", NULL),
                   0);
  assert_non_null(strstr(out, "scalar-float, 1 thread, depth 5, 1 spp"));
  assert_non_null(strstr(out, "PNG/render"));
  assert_non_null(strstr(out, "\nwhitted "));
  assert_non_null(strstr(out, "\nphong "));
  assert_true(folder_is_empty());
  /* A scene whose name starts with '-' (the child read -dash.nff as -d
   * ash.nff and failed) */
  put_text("-dash.nff", small_nff);
  assert_int_equal(run("bench", "--time-to-image", "--scenes", "-dash.nff",
                       "--runs", "1", "-s", "1", "--backends", "scalar-float",
                       NULL),
                   0);
  assert_non_null(strstr(out, "\n-dash "));
  remove_in_folder("-dash.nff");
  EXPECT_USAGE_ERROR("unknown scene 'atlantis'", "bench", "--time-to-image",
                     "--scenes", "atlantis");
  /* A TMPDIR that cannot take the folder is named, with why */
  extra_env = "TMPDIR=/nonexistent-glint-tmp";
  EXPECT_USAGE_ERROR("glint: TMPDIR /nonexistent-glint-tmp: cannot make a "
                     "folder there for the images: No such file or directory",
                     "bench", "--time-to-image", "--scenes", "whitted");
  extra_env = NULL;
}

static void bench_errors(void **state) {
  (void)state;
  EXPECT_USAGE_ERROR("--runs: 0 is outside", "bench", "--runs", "0");
  EXPECT_USAGE_ERROR("--depths", "bench", "--depths", "0-3");
  EXPECT_USAGE_ERROR("--depths", "bench", "--depths", "x");
  /* (it said "the list is empty") */
  EXPECT_USAGE_ERROR("--depths: the range 5-1 runs backwards (write 1-5)",
                     "bench", "--depths", "5-1");
  /* (it said "unknown option 'extra'") */
  EXPECT_USAGE_ERROR("unexpected argument 'extra': glint bench takes options "
                     "only",
                     "bench", "extra");
  EXPECT_USAGE_ERROR("unknown backend 'quantum'", "bench", "--backends",
                     "quantum");
  EXPECT_USAGE_ERROR("unknown scene 'atlantis'", "bench", "--scenes",
                     "atlantis");
  EXPECT_USAGE_ERROR("unknown option", "bench", "--frobnicate");
  EXPECT_USAGE_ERROR("--threads: 'x' is not a whole number", "bench", "-t",
                     "1,x");
  EXPECT_USAGE_ERROR("--spd: /nonexistent/balls-s4.nff: No such file", "bench",
                     "--spd", "/nonexistent");
  EXPECT_USAGE_ERROR("--meshes: /nonexistent/bunny.obj: No such file", "bench",
                     "--meshes", "/nonexistent");
  EXPECT_USAGE_ERROR("--plot: cannot create the folder /proc/glint", "bench",
                     "--plot", "/proc/glint");
  EXPECT_USAGE_ERROR("--depths: '' is not a whole number", "bench", "--depths",
                     "1,,2");
  /* A value twice made two columns alike (and -t 1,1's speed-ups were
   * against the second); "1-2-3" said "'2-3' is not a whole number"; -t
   * with nothing suggested the depths' example. */
  EXPECT_USAGE_ERROR("--depths: 3 is in the list twice", "bench", "--depths",
                     "1-5,3");
  EXPECT_USAGE_ERROR("--threads: 1 is in the list twice", "bench", "-t", "1,1");
  char all_cpus[32];
  snprintf(all_cpus, sizeof all_cpus, "0,%d", glint_cpu_count());
  EXPECT_USAGE_ERROR("--threads: 0 (every CPU this process may use) and",
                     "bench", "-t", all_cpus);
  EXPECT_USAGE_ERROR("--backends: sse is in the list twice", "bench",
                     "--backends", "sse,sse");
  EXPECT_USAGE_ERROR("--backends: an empty name in the list", "bench",
                     "--backends", "auto,");
  EXPECT_USAGE_ERROR("--depths: '1-2-3' is not a value or a range A-B", "bench",
                     "--depths", "1-2-3");
  EXPECT_USAGE_ERROR("--threads: give a list such as 1 or 1,2", "bench", "-t",
                     "");
  /* (it wrote a file named '-') */
  EXPECT_USAGE_ERROR("--csv: '-' would be a file of that name", "bench",
                     "--csv", "-");
  EXPECT_USAGE_ERROR("benchmarks of their own: choose one", "bench",
                     "--time-to-image", "--frames", "2");
  /* Options a benchmark would not use are refused (they were ignored:
   * --spd rendered 512x512 at depth 5 whatever -W or --depths said) */
  EXPECT_USAGE_ERROR("--spd renders the SPD files' own size, 1 spp, depth 5: "
                     "-W is not used",
                     "bench", "--spd", "/nonexistent", "-W", "32");
  EXPECT_USAGE_ERROR("--depths is not used", "bench", "--spd", "/nonexistent",
                     "--depths", "3");
  EXPECT_USAGE_ERROR("--scenes is not used", "bench", "--spd", "/nonexistent",
                     "--scenes", "whitted");
  EXPECT_USAGE_ERROR("--meshes traces 1024x1024 primary rays on one thread, "
                     "shading none: "
                     "-t is not used",
                     "bench", "--meshes", "/nonexistent", "-t", "2");
  EXPECT_USAGE_ERROR("--view renders its frames once a scene, at 1 spp: --runs "
                     "is not used",
                     "bench", "--view", "2", "--runs", "3");
  EXPECT_USAGE_ERROR("a second scene is not used", "bench", "--frames", "2",
                     "--scenes", "whitted,giza");
  EXPECT_USAGE_ERROR("--view renders its frames once a scene, at 1 spp: -s is "
                     "not used",
                     "bench", "--view", "2", "-s", "4");
  EXPECT_USAGE_ERROR("--math is not used", "bench", "--meshes", "/nonexistent",
                     "--math", "fast");
  /* Two scenes of one name would share their rows and plots */
  EXPECT_USAGE_ERROR("--scenes: two scenes named 'whitted'", "bench",
                     "--scenes", "whitted,giza,whitted");
  /* ...and empty names are no scene (",," said "two scenes named ''") */
  EXPECT_USAGE_ERROR("--scenes: an empty name in the list", "bench", "--scenes",
                     ",,");
  EXPECT_USAGE_ERROR("--scenes: an empty name in the list", "bench", "--scenes",
                     "whitted,");
  EXPECT_USAGE_ERROR("--csv: /nonexistent/b.csv: cannot write here", "bench",
                     "--csv", "/nonexistent/b.csv", "--depths", "1", "--scenes",
                     "whitted", "--backends", "scalar-float", "-W", "8", "-H",
                     "8");
  /* --view's scenes are scenes, never glint view's options (--scenes
   * --help printed its help and exited 0) */
  assert_int_equal(run("bench", "--scenes", "--help", "--view", "1", NULL), 2);
  assert_null(strstr(out, "Usage"));
}

/* -t 1,2: every backend at each thread count, side by side. */
static void bench_thread_columns(void **state) {
  (void)state;
  assert_int_equal(run("bench", "--scenes", "whitted", "--depths", "2",
                       "--runs", "1", "-W", "16", "-H", "12", "-s", "1",
                       "--backends", "scalar-float,sse", "-t", "1,2", NULL),
                   0);
  assert_non_null(strstr(out, "scalar-float/1t"));
  assert_non_null(strstr(out, "sse/2t"));
}

/* A backend the CPU lacks is refused; auto falls back to the widest one
 * there is. GLINT_ISA caps the detected instruction sets. */
static void missing_instruction_sets(void **state) {
  (void)state;
  char p[128];
  snprintf(p, sizeof p, "%s/a.png", dir);
  extra_env = "GLINT_ISA=sse";
  EXPECT_USAGE_ERROR("backend 'avx512' is not available with GLINT_ISA=sse",
                     "render", "-b", "avx512");
  EXPECT_USAGE_ERROR("backend 'avx2' is not available with GLINT_ISA=sse",
                     "render", "-b", "avx2");
  assert_int_equal(run("render", "-W", "8", "-H", "8", "-o", "a.png", NULL), 0);
  assert_non_null(strstr(out, ", sse,"));
  unlink(p);
  extra_env = "GLINT_ISA=none";
  EXPECT_USAGE_ERROR("backend 'sse' is not available with GLINT_ISA=none",
                     "render", "-b", "sse");
  /* "the widest stream backend": there is none (it rendered scalar-float) */
  EXPECT_USAGE_ERROR("backend 'stream' is not available with GLINT_ISA=none",
                     "render", "-b", "stream");
  assert_int_equal(run("render", "-W", "8", "-H", "8", "-o", "a.png", NULL), 0);
  assert_non_null(strstr(out, ", scalar-float,"));
  unlink(p);
  extra_env = "GLINT_ISA=bogus";
  EXPECT_USAGE_ERROR("GLINT_ISA='bogus' is not none, sse, avx2 or avx512",
                     "render", "-W", "8", "-H", "8", "-o", "a.png");
  EXPECT_USAGE_ERROR("GLINT_ISA='bogus'", "bench", "--runs", "1");
  extra_env = "GLINT_ISA=scalar"; /* an alias once taken, never said */
  EXPECT_USAGE_ERROR("GLINT_ISA='scalar' is not none, sse, avx2 or avx512",
                     "render", "-W", "8", "-H", "8", "-o", "a.png");
  extra_env = "GLINT_ISA=bogus";
  /* ...but the help still shows (it was refused too) */
  assert_int_equal(run("render", "--help", NULL), 0);
  assert_non_null(strstr(out, "Usage: glint render"));
  extra_env = NULL;
  assert_int_equal(run("--help", NULL), 0);
  assert_non_null(strstr(out, "GLINT_ISA"));
}

/* What a newcomer tried: -W=16, --, -o - with --format. */
static void options_as_people_write_them(void **state) {
  (void)state;
  char p[128];
  assert_int_equal(
      run("render", "-W=16", "-H=12", "-q", "-o", "a.ppm", "--", "giza", NULL),
      0);
  snprintf(p, sizeof p, "%s/a.ppm", dir);
  char head[16];
  slurp(p, head, sizeof head);
  assert_memory_equal(head, "P6\n16 12\n255\n", 13);
  unlink(p);
  EXPECT_USAGE_ERROR("more than one scene", "render", "--", "giza", "whitted");
  /* a '+' before a number, in --region as in -W and -s (it was refused) */
  assert_int_equal(run("render", "-W", "+16", "-s", "+1", "--region",
                       "+2,+3,+4,+5", "-q", "-o", "a.ppm", "giza", NULL),
                   0);
  slurp(p, head, sizeof head);
  assert_memory_equal(head, "P6\n4 5\n255\n", 11);
  unlink(p);

  /* -o -: the image on stdout, the summary on stderr */
  assert_int_equal(
      run("render", "-W", "8", "-H", "6", "-o", "-", "--format", "ppm", NULL),
      0);
  assert_memory_equal(out, "P6\n8 6\n255\n", 11);
  assert_non_null(strstr(err, "(standard output): 8x6"));
  assert_int_equal(run("render", "-W", "8", "-H", "6", "-q", "-o", "-", NULL),
                   0);
  assert_memory_equal(out, "\x89PNG", 4);
  assert_string_equal(err, "");
  EXPECT_USAGE_ERROR("--format applies to -o -", "render", "--format", "ppm",
                     "-o", "a.png");
  EXPECT_USAGE_ERROR("--format: 'jpg' is not png, bmp or ppm", "render", "-o",
                     "-", "--format", "jpg");

  /* more threads than CPUs: done, with a note */
  assert_int_equal(run("render", "-W", "8", "-H", "8", "-t", "64", "-q", "-o",
                       "a.png", NULL),
                   0);
  assert_non_null(strstr(err, "64 threads on the"));
  snprintf(p, sizeof p, "%s/a.png", dir);
  unlink(p);
}

/* threads = 0 means the CPUs this process may use, not all online. */
static void default_threads_follow_the_affinity(void **state) {
  (void)state;
  cpu_set_t saved, one;
  if (sched_getaffinity(0, sizeof saved, &saved) != 0 ||
      CPU_COUNT(&saved) < 2) {
    print_message("SKIPPED: needs 2 CPUs to restrict to 1\n");
    skip();
  }
  int first = 0;
  while (!CPU_ISSET(first, &saved))
    first++;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  assert_int_equal(sched_setaffinity(0, sizeof one, &one), 0);
  int rc = run("render", "-W", "8", "-H", "8", "--stats", "-o", "a.png", NULL);
  sched_setaffinity(0, sizeof saved, &saved);
  assert_int_equal(rc, 0);
  assert_non_null(strstr(out, ", 1 thread\n"));
  char p[128];
  snprintf(p, sizeof p, "%s/a.png", dir);
  unlink(p);
}

/* m.json, a scene of one mesh (tri.obj, a triangle), and `link`, a
 * symbolic link to the mesh, where an output might be written. */
static void put_mesh_scene(const char *link) {
  put_text("tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  put_text("m.json", "{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": "
                     "\"mesh\", \"file\": \"tri.obj\", \"material\": \"m\"}]}");
  char mesh_file[600], link_file[600];
  snprintf(mesh_file, sizeof mesh_file, "%s/tri.obj", dir);
  snprintf(link_file, sizeof link_file, "%s/%s", dir, link);
  assert_int_equal(symlink(mesh_file, link_file), 0);
}

/* One far object makes the hit tolerance larger than the scene's other
 * objects, which then vanish from the image: glint renders it and says so
 * (it said nothing). The same scene without it has no note. */
static void a_far_object_is_noted(void **state) {
  (void)state;
  put_text("near.nff", small_nff);
  char far[256];
  snprintf(far, sizeof far, "%ss 0 0 1e6 1\n", small_nff);
  put_text("far.nff", far);
  assert_int_equal(run("render", "near.nff", "-o", "near.png", NULL), 0);
  assert_null(strstr(err, "note"));
  assert_int_equal(run("render", "far.nff", "-o", "far.png", "-q", NULL), 0);
  if (!strstr(err, "glint: note: far.nff: hits nearer than 100 to a ray's "
                   "start are not seen (1e-4 of the scene's largest "
                   "coordinate, 1e+06), and its smallest object measures "
                   "1: "))
    fail_msg("no note of the far sphere: %s", err);
  char cmd[512];
  snprintf(cmd, sizeof cmd,
           "cd '%s' && rm -f near.nff far.nff near.png far.png", dir);
  assert_int_equal(system(cmd), 0);
}

/* bench --plot runs gnuplot without a shell and quotes names inside its
 * script: a scene or folder named with quotes and a command stays a name
 * (it ran the command through system() before). */
static void bench_plot_names_are_not_commands(void **state) {
  (void)state;
  if (system("command -v gnuplot >/dev/null 2>&1") != 0)
    skip(); /* gnuplot-nox: scripts/install-deps.sh */
  static const char scene[] = "x'; touch INJECTED; echo '.nff";
  put_text(scene, "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 40\n"
                  "hither 1\nresolution 8 8\nl 1 1 -5\n"
                  "f 1 0 0 1 0 1 0 1\ns 0 0 0 1\n");
  assert_int_equal(run("bench", "--scenes", scene, "--depths", "1,2", "--runs",
                       "1", "-s", "1", "--backends", "scalar-float", "--plot",
                       "plots", NULL),
                   0);
  assert_false(exists("INJECTED"));
  /* A pipe where a plot goes: refused before measuring (gnuplot waited on
   * it for ever) */
  char fifo[600];
  snprintf(fifo, sizeof fifo, "%s/plots/s.png", dir);
  assert_int_equal(mkfifo(fifo, 0644), 0);
  put_text("s.nff", small_nff);
  EXPECT_USAGE_ERROR_KEEPING("--plot: plots/s.png: not a regular file", "bench",
                             "--scenes", "s.nff", "--depths", "1", "--runs",
                             "1", "--backends", "scalar-float", "--plot",
                             "plots");
  remove_in_folder("plots/s.png");
  /* A plot's file that is a link to a scene file (the plot replaced the
   * scene with a PNG), or --csv's file too: refused before measuring */
  char link[600];
  put_text("victim.json", "{}\n");
  snprintf(link, sizeof link, "%s/plots/s.dat", dir);
  assert_int_equal(symlink("../victim.json", link), 0);
  EXPECT_USAGE_ERROR_KEEPING(
      "--plot: plots/s.dat: a link to plots/../victim.json, "
      "a scene or mesh file",
      "bench", "--scenes", "s.nff", "--depths", "1", "--runs", "1",
      "--backends", "scalar-float", "--plot", "plots");
  assert_int_equal(unlink(link), 0);
  char kept_scene[64];
  snprintf(link, sizeof link, "%s/victim.json", dir);
  slurp(link, kept_scene, sizeof kept_scene);
  assert_string_equal(kept_scene, "{}\n");
  remove_in_folder("victim.json");
  EXPECT_USAGE_ERROR_KEEPING("--plot: plots/s.gp is --csv's file too", "bench",
                             "--scenes", "s.nff", "--depths", "1", "--runs",
                             "1", "--backends", "scalar-float", "--plot",
                             "plots", "--csv", "./plots/s.gp");
  /* A run refused for its scene makes no folder (an empty one was left),
   * and a line break, which gnuplot cannot take, is refused before the
   * measurements (the plot failed after them) */
  EXPECT_USAGE_ERROR_KEEPING("nosuch.nff", "bench", "--scenes", "nosuch.nff",
                             "--plot", "newplots");
  assert_false(exists("newplots"));
  EXPECT_USAGE_ERROR_KEEPING("--plot: the folder's name has a line break",
                             "bench", "--scenes", "s.nff", "--plot", "p\nx");
  assert_false(exists("p\nx"));
  /* a link to nothing where the folder goes: refused up front (the whole
   * benchmark ran, then gnuplot "could not draw") */
  char dangling[600];
  snprintf(dangling, sizeof dangling, "%s/dangling", dir);
  assert_int_equal(symlink("nowhere", dangling), 0);
  EXPECT_USAGE_ERROR_KEEPING("--plot: dangling is a link to nothing", "bench",
                             "--scenes", "s.nff", "--plot", "dangling");
  remove_in_folder("dangling");
  remove_in_folder("s.nff");
  static const char *made[] = {"plots/x'; touch INJECTED; echo '.png",
                               "plots/x'; touch INJECTED; echo '.dat",
                               "plots/x'; touch INJECTED; echo '.gp", scene};
  for (size_t i = 0; i < sizeof made / sizeof *made; i++) {
    assert_true(exists(made[i]));
    remove_in_folder(made[i]);
  }
  assert_int_equal(remove_in_folder("plots"), 0);
}

/* -o - into a pipe whose reader has gone (glint render -o - | head): the
 * write fails, glint says so and exits 2, not killed by SIGPIPE. */
static void a_closed_pipe_is_an_error(void **state) {
  (void)state;
  int fds[2];
  assert_int_equal(pipe(fds), 0);
  close(fds[0]); /* no reader */
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  char *argv[] = {"glint", "render",   "whitted", "-W", "64", "-H", "48",
                  "-q",    "--format", "ppm",     "-o", "-",  NULL};
  pid_t pid;
  assert_int_equal(posix_spawn(&pid, GLINT_EXE, &fa, NULL, argv, environ), 0);
  posix_spawn_file_actions_destroy(&fa);
  close(fds[1]);
  int status;
  assert_int_equal(waitpid(pid, &status, 0), pid);
  if (!WIFEXITED(status))
    fail_msg("glint was killed by signal %d", WTERMSIG(status));
  assert_int_equal(WEXITSTATUS(status), 2);
}

/* Runs glint with standard stream `closed` closed, the other one of stdout
 * and stderr into err; its exit status. */
static int run_with_closed(int closed, char *const argv[]) {
  char path[600];
  snprintf(path, sizeof path, "%s/.other", dir);
  pid_t pid = spawn_glint(argv, environ, closed == 1 ? NULL : path,
                          closed == 2 ? NULL : path);
  return exit_status(pid, path);
}

/* A closed standard stream (glint render >&-) is /dev/null to glint: the
 * image is written whole and the status is 0 (it was 2, "Bad file
 * descriptor", after the image was written: the first file glint opened
 * took the stream's number). -o - is refused when standard output is
 * closed; an error with standard error closed is still status 2, with
 * nothing written. */
static void closed_standard_streams(void **state) {
  (void)state;
  char closed_png[600], never_png[600];
  snprintf(closed_png, sizeof closed_png, "%s/closed.png", dir);
  snprintf(never_png, sizeof never_png, "%s/never.png", dir);
  char *render[] = {"glint", "render", "whitted", "-W",       "16",
                    "-H",    "12",     "-o",      closed_png, NULL};
  assert_int_equal(run_with_closed(1, render), 0);
  assert_string_equal(err, "");
  assert_int_equal(run("render", "whitted", "-W", "16", "-H", "12", "-q", "-o",
                       "open.png", NULL),
                   0);
  assert_int_equal(run("compare", "closed.png", "open.png", NULL), 0);
  assert_non_null(strstr(out, "identical"));
  char *to_stdout[] = {"glint", "render", "-W", "16", "-H",
                       "12",    "-o",     "-",  NULL};
  assert_int_equal(run_with_closed(1, to_stdout), 2);
  assert_string_equal(err, "glint: -o -: standard output is closed; redirect "
                           "it to a file or a program\n");
  char *missing[] = {"glint", "render", "nowhere.nff", "-o", never_png, NULL};
  assert_int_equal(run_with_closed(2, missing), 2);
  assert_false(exists("never.png"));
  assert_int_equal(remove_in_folder("closed.png"), 0);
  assert_int_equal(remove_in_folder("open.png"), 0);
  assert_true(folder_is_empty());
}

/* What standard output cannot take is an error (exit 2, said on standard
 * error): glint compare > /dev/full lost its PSNR line and exited 0. */
static void a_full_standard_output_is_an_error(void **state) {
  (void)state;
  if (access("/dev/full", W_OK) != 0) {
    print_message("no /dev/full here\n");
    skip();
  }
  assert_int_equal(run("render", "whitted", "-W", "16", "-H", "12", "-q", "-o",
                       "a.png", NULL),
                   0);
  char a_png[600], err_path[600];
  snprintf(a_png, sizeof a_png, "%s/a.png", dir);
  snprintf(err_path, sizeof err_path, "%s/err.txt", dir);
  const char *commands[][10] = {
      {"glint", "compare", a_png, a_png, NULL},
      {"glint", "--version", NULL},
      {"glint", "render", "--help", NULL},
      /* an image: named as the output, which the message alone did not */
      {"glint", "render", "-W", "8", "-H", "6", "-q", "-o", "-", NULL}};
  for (size_t i = 0; i < sizeof commands / sizeof *commands; i++) {
    pid_t pid =
        spawn_glint((char *const *)commands[i], environ, "/dev/full", err_path);
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    char text[4096];
    slurp(err_path, text, sizeof text);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 2)
      fail_msg("glint %s > /dev/full: status %d, want exit 2", commands[i][1],
               status);
    if (!strstr(text, i == 3 ? "glint: standard output (-o -): writing the "
                               "image failed: No space left on device"
                             : "glint: writing to standard output failed: No "
                               "space left on device"))
      fail_msg("glint %s > /dev/full: stderr '%s'", commands[i][1], text);
  }
  assert_int_equal(remove_in_folder("err.txt"), 0);
  assert_int_equal(remove_in_folder("a.png"), 0);
  assert_true(folder_is_empty());
}

/* A file past the size limit (ulimit -f) is a write error glint reports,
 * the old file kept and no temporary file left: SIGXFSZ killed it mid-write
 * with the temporary file in the folder. */
static void a_file_past_the_size_limit_is_an_error(void **state) {
  (void)state;
  put_text("limited.png", "old");
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    struct rlimit limit = {20 * 1024, 20 * 1024};
    int null = open("/dev/null", O_WRONLY);
    if (setrlimit(RLIMIT_FSIZE, &limit) != 0 || chdir(dir) != 0 || null < 0 ||
        dup2(null, 2) < 0)
      _exit(99);
    execl(GLINT_EXE, "glint", "render", "whitted", "-t", "1", "-q", "-o",
          "limited.png", (char *)NULL);
    _exit(98);
  }
  int status;
  assert_int_equal(waitpid(pid, &status, 0), pid);
  if (!WIFEXITED(status))
    fail_msg("glint was killed by signal %d", WTERMSIG(status));
  assert_int_equal(WEXITSTATUS(status), 2);
  char kept[16];
  char path[600];
  snprintf(path, sizeof path, "%s/limited.png", dir);
  slurp(path, kept, sizeof kept);
  assert_string_equal(kept, "old");
  assert_int_equal(remove_in_folder("limited.png"), 0);
  assert_true(folder_is_empty()); /* no temporary file */
}

/* A plot that cannot be written whole (here past the size limit, as on a
 * full disk) is an error, and the old plot stays: gnuplot exits 0 when its
 * output fails, and a good plot was replaced by a truncated one with exit
 * status 0 and no word. */
static void a_plot_past_the_size_limit_is_an_error(void **state) {
  (void)state;
  if (system("command -v gnuplot >/dev/null 2>&1") != 0)
    skip(); /* gnuplot-nox: scripts/install-deps.sh */
  char plots[600];
  snprintf(plots, sizeof plots, "%s/plots", dir);
  assert_int_equal(mkdir(plots, 0755), 0);
  put_text("plots/whitted.png", "old");
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    struct rlimit limit = {8 * 1024, 8 * 1024}; /* the plot: about 26 KiB */
    int null = open("/dev/null", O_WRONLY);
    if (chdir(dir) != 0 || null < 0 || dup2(null, 1) < 0)
      _exit(99);
    int err = open("plot.err", O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (err < 0 || dup2(err, 2) < 0 || setrlimit(RLIMIT_FSIZE, &limit) != 0)
      _exit(99);
    execl(GLINT_EXE, "glint", "bench", "--scenes", "whitted", "--depths", "1,2",
          "--backends", "scalar-float", "--runs", "1", "-W", "8", "-H", "6",
          "-s", "1", "--plot", "plots", (char *)NULL);
    _exit(98);
  }
  int status;
  assert_int_equal(waitpid(pid, &status, 0), pid);
  if (!WIFEXITED(status))
    fail_msg("glint was killed by signal %d", WTERMSIG(status));
  assert_int_equal(WEXITSTATUS(status), 2);
  char kept[16], path[700], said[1024];
  snprintf(path, sizeof path, "%s/plot.err", dir);
  slurp(path, said, sizeof said);
  assert_int_equal(remove_in_folder("plot.err"), 0);
  assert_non_null(strstr(said, "--plot: gnuplot could not write plots/"
                               "whitted.png whole"));
  snprintf(path, sizeof path, "%s/whitted.png", plots);
  slurp(path, kept, sizeof kept);
  assert_string_equal(kept, "old");
  DIR *d = opendir(plots);
  assert_non_null(d);
  int entries = 0;
  for (struct dirent *e; (e = readdir(d));)
    if (e->d_name[0] != '.' || strstr(e->d_name, ".tmp"))
      entries++, printf("plots/%s\n", e->d_name);
  closedir(d);
  assert_int_equal(entries, 3); /* whitted.png, .dat and .gp: no temporary */
  assert_int_equal(remove_in_folder("plots/whitted.png"), 0);
  assert_int_equal(remove_in_folder("plots/whitted.dat"), 0);
  assert_int_equal(remove_in_folder("plots/whitted.gp"), 0);
  assert_int_equal(rmdir(plots), 0);
}

/* Whether glint runs under AddressSanitizer (gcc's macro, clang's
 * feature), which reserves terabytes of address space at start-up. */
#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ADDRESS_SANITIZER 1
#endif
#endif
#ifndef UNDER_ADDRESS_SANITIZER
#define UNDER_ADDRESS_SANITIZER 0
#endif

/* Runs glint with the stack limit (ulimit -s) `soft` and `hard` bytes,
 * stderr into err; its exit status. */
static int run_with_stack_limit(rlim_t soft, rlim_t hard, const char *scene,
                                const char *depth, const char *output) {
  char err_path[128];
  snprintf(err_path, sizeof err_path, "%s/.stderr", dir);
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    struct rlimit limit = {soft, hard};
    int errors = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (setrlimit(RLIMIT_STACK, &limit) != 0 || chdir(dir) != 0 || errors < 0 ||
        dup2(errors, 2) < 0)
      _exit(99);
    execl(GLINT_EXE, "glint", "render", scene, "-W", "32", "-H", "24", "-d",
          depth, "-q", "-o", output, (char *)NULL);
    _exit(98);
  }
  return exit_status(pid, err_path);
}

/* A small stack limit (ulimit -s 64) crashed glint in cJSON's recursion
 * and in the beam tracers' at depth 64. glint raises a soft limit to 8 MiB
 * and renders (test_json and test_renderer load and render on small
 * threads, which no limit raises); a hard limit below what it needs is
 * said, with exit 1. (Not under AddressSanitizer, whose start-up needs
 * more than 64 KiB.) */
static void a_small_stack_limit(void **state) {
  (void)state;
  if (UNDER_ADDRESS_SANITIZER)
    skip();
  struct rlimit saved;
  getrlimit(RLIMIT_STACK, &saved);
  const rlim_t small = (rlim_t)64 << 10;
  /* 1000 nested arrays (cJSON takes 1000): refused by name, not parsed
   * by recursion */
  char deep[1024] = "{\"camera\": ";
  memset(deep + strlen(deep), '[', 1000);
  put_text("deep.json", deep);
  assert_int_equal(
      run_with_stack_limit(small, saved.rlim_max, "deep.json", "5", "d.png"),
      2);
  assert_non_null(strstr(err, "nested deeper than 100 levels"));
  assert_int_equal(remove_in_folder("deep.json"), 0);
  assert_int_equal(
      run_with_stack_limit(small, saved.rlim_max, "billiard", "64", "b.png"),
      0);
  assert_int_equal(remove_in_folder("b.png"), 0);
  put_text("b.png", "old");
  assert_int_equal(
      run_with_stack_limit(small, small, "billiard", "64", "b.png"), 1);
  assert_non_null(strstr(err, "glint: the stack limit (ulimit -s) is 64 KiB; "
                              "glint needs at least 512 KiB"));
  char kept[16];
  char path[600];
  snprintf(path, sizeof path, "%s/b.png", dir);
  slurp(path, kept, sizeof kept);
  assert_string_equal(kept, "old");
  assert_int_equal(remove_in_folder("b.png"), 0);
  assert_true(folder_is_empty());
}

/* Memory that cannot be had is exit status 1 (glint --help), from every
 * place that asks for it: the image, a scene's meshes, the check of
 * --frames' files. A BMP is held whole
 * (bottom row first); a PNG would need only bands of it. (Not under
 * AddressSanitizer, which reserves terabytes of address space.) */
static void out_of_memory_exits_1(void **state) {
  (void)state;
  if (UNDER_ADDRESS_SANITIZER)
    skip();
  struct rlimit saved, small;
  getrlimit(RLIMIT_AS, &saved);
  small = saved;
  small.rlim_cur = (rlim_t)600 << 20; /* a 16384x16384 BMP needs more */
  setrlimit(RLIMIT_AS, &small);
  int rc = run("render", "whitted", "-W", "16384", "-H", "16384", "-d", "1",
               "-s", "1", "-o", "big.bmp", NULL);
  char bench_err[2][sizeof err];
  /* bench's own modes too (they exited 2) */
  int frames = run("bench", "--frames", "2", "--scenes", "whitted", "-W",
                   "16384", "-H", "16384", "--depths", "1", NULL);
  snprintf(bench_err[0], sizeof bench_err[0], "%s", err);
  int to_image =
      run("bench", "--time-to-image", "--scenes", "whitted", "-W", "16384",
          "-H", "16384", "--depths", "1", "--runs", "1", NULL);
  snprintf(bench_err[1], sizeof bench_err[1], "%s", err);
  /* checking 4 million frames' files: a table of 128 MiB (it exited 2) */
  put_text("many.json",
           "{\"camera\": {\"from\": [0, 2, 6], \"at\": [0, 1, 0]},"
           " \"materials\": {\"m\": {}}, \"objects\": [{\"type\": \"sphere\","
           " \"center\": [0, 1, 0], \"radius\": 1, \"material\": \"m\"}],"
           " \"animation\": {\"fps\": 24, \"frames\": [1,"
           " 99999999], \"camera\": {\"orbit\": {\"center\": [0, 1, 0],"
           " \"radius\": 6}}}}");
  small.rlim_cur = (rlim_t)100 << 20;
  setrlimit(RLIMIT_AS, &small);
  int many = run("render", "many.json", "--frames", "1-4000000", "-W", "8",
                 "-H", "8", "-o", "f%08d.png", NULL);
  char many_err[sizeof err];
  snprintf(many_err, sizeof many_err, "%s", err);
  setrlimit(RLIMIT_AS, &saved);
  assert_int_equal(remove_in_folder("many.json"), 0);
  assert_int_equal(many, 1);
  assert_non_null(strstr(many_err, "out of memory checking 4000000 frames"));
  assert_int_equal(rc, 1);
  assert_int_equal(frames, 1);
  assert_non_null(strstr(bench_err[0], "out of memory for a 16384x16384 film"));
  assert_int_equal(to_image, 1);
  assert_non_null(strstr(bench_err[1], "out of memory"));
  assert_true(folder_is_empty());
}

/* A new image has 0666 less the umask; one written over keeps its own
 * permissions. */
static void written_files_keep_their_permissions(void **state) {
  (void)state;
  char p[256];
  snprintf(p, sizeof p, "%s/mode.png", dir);
  mode_t saved = umask(027);
  int rc = run("render", "-W", "8", "-H", "8", "-q", "-o", "mode.png", NULL);
  umask(saved);
  assert_int_equal(rc, 0);
  struct stat sb;
  assert_int_equal(stat(p, &sb), 0);
  assert_int_equal(sb.st_mode & 07777, 0640);
  assert_int_equal(chmod(p, 0604), 0);
  assert_int_equal(
      run("render", "-W", "8", "-H", "8", "-q", "-o", "mode.png", NULL), 0);
  assert_int_equal(stat(p, &sb), 0);
  assert_int_equal(sb.st_mode & 07777, 0604);
  remove_in_folder("mode.png");
  assert_true(folder_is_empty());
}

/* The bytes of NAME in the test folder; *size its length. */
static char *file_bytes(const char *name, long *size) {
  char p[256];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  FILE *f = fopen(p, "rb");
  if (!f)
    fail_msg("%s is missing", name);
  fseek(f, 0, SEEK_END);
  *size = ftell(f);
  rewind(f);
  char *data = malloc((size_t)*size + 1);
  assert_int_equal(fread(data, 1, (size_t)*size, f), (size_t)*size);
  fclose(f);
  return data;
}

/* Asserts that NAME in the test folder still begins with `start` (and is
 * longer, where `longer`): a file a refused command had to leave alone. */
static void assert_kept(const char *name, const char *start, int longer) {
  long n;
  char *kept = file_bytes(name, &n);
  size_t len = strlen(start);
  if (n < (long)len + longer || memcmp(kept, start, len) != 0)
    fail_msg("%s was changed", name);
  free(kept);
}

/* The CSV appears only when the benchmark has run to its end: a bad scene
 * leaves an existing file as it was, and the CSV cannot be a scene. */
static void bench_csv_keeps_files_on_error(void **state) {
  (void)state;
  put_text("keep.csv", "precious");
  EXPECT_USAGE_ERROR_KEEPING("unknown scene 'atlantis'", "bench", "--scenes",
                             "whitted,atlantis", "--csv", "keep.csv");
  put_text("s.nff", small_nff);
  EXPECT_USAGE_ERROR_KEEPING("--csv: s.nff is a scene of this benchmark",
                             "bench", "--scenes", "s.nff", "--depths", "1",
                             "--runs", "1", "--backends", "scalar-float",
                             "--csv", "s.nff");
  long n;
  char *kept = file_bytes("keep.csv", &n);
  assert_true(n == 8 && memcmp(kept, "precious", 8) == 0);
  free(kept);
  assert_kept("s.nff", "v\nfrom", 1);
  /* ...nor a mesh the scene reads, directly or through a link (the mesh
   * was replaced by the CSV, exit 0) */
  put_mesh_scene("results.csv");
  EXPECT_USAGE_ERROR_KEEPING("--csv: tri.obj is a scene or mesh file", "bench",
                             "--scenes", "m.json", "--depths", "1", "--runs",
                             "1", "--backends", "scalar-float", "--csv",
                             "tri.obj");
  EXPECT_USAGE_ERROR_KEEPING("--csv: results.csv is a scene or mesh file",
                             "bench", "--scenes", "m.json", "--depths", "1",
                             "--runs", "1", "--backends", "scalar-float",
                             "--csv", "results.csv");
  assert_kept("tri.obj", "v -1 -1 0", 1);
  assert_int_equal(remove_in_folder("results.csv"), 0);
  assert_int_equal(remove_in_folder("tri.obj"), 0);
  assert_int_equal(remove_in_folder("m.json"), 0);
  EXPECT_USAGE_ERROR_KEEPING("--csv: . is a folder", "bench", "--scenes",
                             "s.nff", "--csv", ".");
  EXPECT_USAGE_ERROR_KEEPING("--csv: the name is empty", "bench", "--scenes",
                             "s.nff", "--csv", "");
  /* A pipe (or a device) is not replaced by a file, directly or through a
   * link (root's bench --csv /dev/full replaced the device) */
  char fifo[600], link_to_fifo[600];
  snprintf(fifo, sizeof fifo, "%s/pipe.csv", dir);
  snprintf(link_to_fifo, sizeof link_to_fifo, "%s/link.csv", dir);
  assert_int_equal(mkfifo(fifo, 0644), 0);
  assert_int_equal(symlink(fifo, link_to_fifo), 0);
  EXPECT_USAGE_ERROR_KEEPING("--csv: pipe.csv: not a regular file", "bench",
                             "--scenes", "s.nff", "--csv", "pipe.csv");
  EXPECT_USAGE_ERROR_KEEPING("--csv: link.csv: not a regular file", "bench",
                             "--scenes", "s.nff", "--csv", "link.csv");
  struct stat sb;
  assert_int_equal(stat(fifo, &sb), 0);
  assert_true(S_ISFIFO(sb.st_mode));
  assert_int_equal(remove_in_folder("link.csv"), 0);
  assert_int_equal(remove_in_folder("pipe.csv"), 0);
  EXPECT_USAGE_ERROR_KEEPING("--spd: the name is empty", "bench", "--spd", "");
  EXPECT_USAGE_ERROR_KEEPING("--meshes: the name is empty", "bench", "--meshes",
                             "");
  assert_string_equal(out, ""); /* refused before measuring */
  assert_int_equal(remove_in_folder("keep.csv"), 0);
  assert_int_equal(remove_in_folder("s.nff"), 0);
  assert_true(folder_is_empty());
}

/* An output linked to the scene would replace it (images are written
 * through links): refused, the scene kept; the same for a mesh. */
static void output_linked_to_the_scene(void **state) {
  (void)state;
  put_text("linked.nff", small_nff);
  char scene_file[600], link_file[600];
  snprintf(scene_file, sizeof scene_file, "%s/linked.nff", dir);
  snprintf(link_file, sizeof link_file, "%s/linked.png", dir);
  assert_int_equal(symlink(scene_file, link_file), 0);
  EXPECT_USAGE_ERROR_KEEPING("linked.png: that is the scene file linked.nff",
                             "render", "linked.nff", "-o", "linked.png");
  assert_kept("linked.nff", "v\nfrom", 1);
  assert_int_equal(remove_in_folder("linked.png"), 0);
  assert_int_equal(remove_in_folder("linked.nff"), 0);
  /* So would one linked to a mesh of the scene, or any scene or mesh file
   * (it replaced tri.obj). */
  put_mesh_scene("out.png");
  EXPECT_USAGE_ERROR_KEEPING("out.png: a link to ", "render", "m.json", "-o",
                             "out.png");
  assert_non_null(strstr(err, "tri.obj, a scene or mesh file (.nff, .json, "
                              ".obj, .ply): the image would replace it"));
  assert_kept("tri.obj", "v -1 -1 0", 1);
  /* ...also where the mesh is itself a link to a file of another name
   * (the check looked at the chain's last name only) */
  char blob[600], chained[600], tri[600], out_png[600];
  snprintf(blob, sizeof blob, "%s/blob", dir);
  snprintf(chained, sizeof chained, "%s/chained.obj", dir);
  snprintf(tri, sizeof tri, "%s/tri.obj", dir);
  snprintf(out_png, sizeof out_png, "%s/out.png", dir);
  assert_int_equal(rename(tri, blob), 0);
  assert_int_equal(symlink("blob", chained), 0);
  assert_int_equal(remove_in_folder("out.png"), 0);
  assert_int_equal(symlink("chained.obj", out_png), 0);
  put_text("m.json", "{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": "
                     "\"mesh\", \"file\": \"chained.obj\", \"material\": "
                     "\"m\"}]}");
  EXPECT_USAGE_ERROR_KEEPING("out.png: a link to ", "render", "m.json", "-o",
                             "out.png");
  assert_non_null(strstr(err, "chained.obj, a scene or mesh file"));
  assert_kept("blob", "v -1 -1 0", 1);
  assert_int_equal(remove_in_folder("out.png"), 0);
  assert_int_equal(remove_in_folder("chained.obj"), 0);
  assert_int_equal(remove_in_folder("blob"), 0);
  assert_int_equal(remove_in_folder("m.json"), 0);
  assert_true(folder_is_empty());
}

/* Without -o, the image is named after the scene: its base name without
 * the extension, and without .gz (it wrote s.json.png for s.json.gz). */
static void default_output_is_named_after_the_scene(void **state) {
  (void)state;
  put_text("s.nff", small_nff);
  char cmd[700];
  snprintf(cmd, sizeof cmd, "gzip '%s/s.nff'", dir);
  assert_int_equal(system(cmd), 0);
  assert_int_equal(run("render", "s.nff.gz", "-q", NULL), 0);
  assert_true(exists("s.png"));
  assert_int_equal(remove_in_folder("s.png"), 0);
  assert_int_equal(remove_in_folder("s.nff.gz"), 0);
  assert_true(folder_is_empty());
}

/* The benchmark modes besides the scene benchmark: --frames past 256
 * frames (a median of a fixed 256 crashed it), -W alone for a child glint
 * (passed as -H 0), --csv and --plot where they are not written (ignored,
 * an empty --plot folder made), --spd's scenes as the CSV (overwritten),
 * and the CSV through a link (the link was replaced). */
static void bench_modes_and_their_files(void **state) {
  (void)state;
  assert_int_equal(run("bench", "--frames", "300", "--scenes", "whitted", "-W",
                       "8", "-H", "8", "-s", "1", "--depths", "1", "--backends",
                       "scalar-float", "-t", "1", NULL),
                   0);
  assert_non_null(strstr(out, "one renderer"));
  /* without --scenes: Whitted, the default list's first (README's example) */
  assert_int_equal(run("bench", "--frames", "2", "-W", "8", "-H", "8", "-s",
                       "1", "--backends", "scalar-float", NULL),
                   0);
  assert_non_null(strstr(out, "one renderer"));
  assert_int_equal(run("bench", "--time-to-image", "--scenes", "whitted", "-W",
                       "16", "-s", "1", "--runs", "1", "--backends",
                       "scalar-float", NULL),
                   0);
  assert_non_null(strstr(out, "\nwhitted "));
  EXPECT_USAGE_ERROR("--csv is written by the scene benchmark and --spd only",
                     "bench", "--frames", "3", "--scenes", "whitted", "--csv",
                     "f.csv");
  EXPECT_USAGE_ERROR("--plot is written by the scene benchmark only", "bench",
                     "--view", "2", "--plot", "plots");
  char spd[600];
  snprintf(spd, sizeof spd, "%s/spd", dir);
  assert_int_equal(mkdir(spd, 0755), 0);
  put_text("spd/balls-s4.nff", small_nff);
  EXPECT_USAGE_ERROR_KEEPING("--csv: spd/balls-s4.nff is a scene of this "
                             "benchmark",
                             "bench", "--spd", "spd", "--csv",
                             "spd/balls-s4.nff");
  assert_kept("spd/balls-s4.nff", "v\nfrom", 1);
  assert_int_equal(remove_in_folder("spd/balls-s4.nff"), 0);
  assert_int_equal(rmdir(spd), 0);
  put_text("target.csv", "old");
  char target[600], link_path[600];
  snprintf(target, sizeof target, "%s/target.csv", dir);
  snprintf(link_path, sizeof link_path, "%s/link.csv", dir);
  assert_int_equal(symlink(target, link_path), 0);
  assert_int_equal(run("bench", "--scenes", "whitted", "-W", "8", "-H", "8",
                       "-s", "1", "--depths", "1", "--backends", "scalar-float",
                       "--runs", "1", "--csv", "link.csv", NULL),
                   0);
  struct stat sb;
  assert_int_equal(lstat(link_path, &sb), 0);
  assert_true(S_ISLNK(sb.st_mode));
  assert_kept("target.csv", "scene,depth", 1);
  assert_int_equal(remove_in_folder("link.csv"), 0);
  assert_int_equal(remove_in_folder("target.csv"), 0);
  assert_true(folder_is_empty());
}

static const char orbit_scene[] =
    "{\"camera\": {\"from\": [0, 2, 6], \"at\": [0, 1, 0]},\n"
    " \"image\": {\"width\": 32, \"height\": 24},\n"
    " \"lights\": [{\"position\": [-4, 8, 6], \"color\": [1, 1, 1]}],\n"
    " \"materials\": {\"m\": {\"color\": [0.9, 0.2, 0.2], \"ks\": 0.3}},\n"
    " \"objects\": [{\"type\": \"sphere\", \"center\": [0, 1, 0], "
    "\"radius\": 1, \"material\": \"m\"},\n"
    "  {\"type\": \"plane\", \"point\": [0, 0, 0], \"normal\": [0, 1, 0], "
    "\"material\": \"m\"}],\n"
    " \"animation\": {\"fps\": 24, \"frames\": [1, 48], \"camera\": "
    "{\"orbit\": {\"center\": [0, 1, 0], \"radius\": 6, \"height\": 1}}}}\n";

/* --frames: a file a frame, named by the pattern or numbered before the
 * extension; each is what glint render writes for the camera of its time;
 * --resume keeps what is there; mistakes are named. */
static void frames_of_an_animation(void **state) {
  (void)state;
  put_text("anim.json", orbit_scene);
  assert_int_equal(
      run("render", "anim.json", "--frames", "1-3", "-o", "f%02d.png", NULL),
      0);
  assert_true(exists("f01.png") && exists("f02.png") && exists("f03.png"));
  assert_false(exists("f04.png"));
  assert_non_null(strstr(out, "frame 2 (t = 0.042 s): f02.png"));
  assert_non_null(strstr(out, "3 frames written in "));

  /* Frame 2 is glint render of the scene with that camera (7.5 degrees
   * round: 360 over 48 frames), written exactly. */
  glint_scene *scene;
  ASSERT_OK(glint_scene_load_memory(orbit_scene, strlen(orbit_scene),
                                    "anim.json", &scene, &e_));
  glint_camera c;
  ASSERT_OK(glint_scene_camera_at(scene, 1.0 / 24, &c, &e_));
  glint_scene_destroy(scene);
  char still[2048];
  snprintf(still, sizeof still,
           "%.*s\"camera\": {\"from\": [%.17g, %.17g, %.17g], \"at\": "
           "[%.17g, %.17g, %.17g], \"fov\": %.17g},%s",
           1, orbit_scene, c.from.x, c.from.y, c.from.z, c.at.x, c.at.y, c.at.z,
           c.fov_x_degrees, strstr(orbit_scene, "\n \"image\""));
  /* ... without its animation block */
  *strstr(still, ",\n \"animation\"") = '\0';
  strcat(still, "}\n");
  put_text("still.json", still);
  assert_int_equal(run("render", "still.json", "-o", "still.png", "-q", NULL),
                   0);
  long na, nb;
  char *a = file_bytes("f02.png", &na), *b = file_bytes("still.png", &nb);
  assert_int_equal(na, nb);
  assert_memory_equal(a, b, (size_t)na);
  free(a);
  free(b);

  /* A frame whose file cannot be written (a folder under its name) stops
   * the run before any frame is: frame 1 was written over before. */
  put_text("f01.png", "precious");
  char folder[600];
  snprintf(folder, sizeof folder, "%s/f03.png", dir);
  assert_int_equal(remove_in_folder("f03.png"), 0);
  assert_int_equal(mkdir(folder, 0755), 0);
  EXPECT_USAGE_ERROR_KEEPING("f03.png: is a directory; no frame was written",
                             "render", "anim.json", "--frames", "1-3", "-o",
                             "f%02d.png");
  long nk;
  char *f01 = file_bytes("f01.png", &nk);
  assert_true(nk == 8 && memcmp(f01, "precious", 8) == 0);
  free(f01);
  assert_int_equal(rmdir(folder), 0);
  assert_int_equal(
      run("render", "anim.json", "--frames", "1-3", "-o", "f%02d.png", NULL),
      0);

  /* Two frames whose names lead to one file through a link (the later
   * frame replaced the earlier, and the run said all were written): a
   * link to another frame's file, and a frame's folder a link to
   * another's. */
  char link[600];
  snprintf(link, sizeof link, "%s/f03.png", dir);
  assert_int_equal(remove_in_folder("f03.png"), 0);
  assert_int_equal(symlink("f01.png", link), 0);
  EXPECT_USAGE_ERROR_KEEPING("frames 1 and 3 would both be written to ",
                             "render", "anim.json", "--frames", "1-3", "-o",
                             "f%02d.png");
  assert_non_null(strstr(err, "/f01.png (as f01.png and f03.png, through a "
                              "link); no frame was written"));
  assert_int_equal(unlink(link), 0);
  snprintf(link, sizeof link, "%s/shot2", dir);
  snprintf(folder, sizeof folder, "%s/shot1", dir);
  assert_int_equal(mkdir(folder, 0755), 0);
  assert_int_equal(symlink("shot1", link), 0);
  EXPECT_USAGE_ERROR_KEEPING("frames 1 and 2 would both be written to ",
                             "render", "anim.json", "--frames", "1-3", "-o",
                             "shot%d/f.png");
  assert_false(exists("shot3")); /* made, and taken away again */
  assert_int_equal(unlink(link), 0);
  assert_int_equal(rmdir(folder), 0);
  assert_int_equal(
      run("render", "anim.json", "--frames", "1-3", "-o", "f%02d.png", NULL),
      0);

  /* A folder in -o that is missing is made. */
  assert_int_equal(run("render", "anim.json", "--frames", "5", "-o",
                       "sub/deeper/f%d.png", "-q", NULL),
                   0);
  assert_true(exists("sub/deeper/f5.png"));
  /* A refused run takes away the folders it made (the number in a
   * folder's name; frame 3's file blocked by a folder), and no others. */
  char blocked[600];
  const char *const folders[] = {"in3", "in3/deep", "in3/deep/f.png"};
  for (int k = 0; k < 3; k++) {
    snprintf(blocked, sizeof blocked, "%s/%s", dir, folders[k]);
    assert_int_equal(mkdir(blocked, 0755), 0);
  }
  EXPECT_USAGE_ERROR_KEEPING(
      "in3/deep/f.png: is a directory; no frame was written", "render",
      "anim.json", "--frames", "1-3", "-o", "in%d/deep/f.png");
  assert_false(exists("in1"));
  assert_false(exists("in2"));
  assert_true(exists("in3/deep/f.png"));

  /* Numbers before the extension; the default name is the scene's. */
  assert_int_equal(
      run("render", "anim.json", "--frames", "48", "-o", "out.png", "-q", NULL),
      0);
  assert_true(exists("out0048.png"));
  assert_int_equal(run("render", "anim.json", "--frames", "7", "-q", NULL), 0);
  assert_true(exists("anim0007.png"));
  /* %% is a % with or without a number in the name. */
  assert_int_equal(run("render", "anim.json", "--frames", "3", "-o",
                       "100%%.png", "-q", NULL),
                   0);
  assert_true(exists("100%0003.png"));
  assert_int_equal(run("render", "anim.json", "--frames", "3", "-o",
                       "p%%%d.png", "-q", NULL),
                   0);
  assert_true(exists("p%3.png"));
  /* A % in the scene's name is a % of the default name (we%d.json made
   * we1.png; 100%.json was refused as a bad pattern). */
  put_text("we%d.json", orbit_scene);
  assert_int_equal(run("render", "we%d.json", "--frames", "2", "-q", NULL), 0);
  assert_true(exists("we%d0002.png"));
  assert_int_equal(remove_in_folder("we%d0002.png"), 0);
  assert_int_equal(remove_in_folder("we%d.json"), 0);
  /* A frame linked to the scene would replace it: refused, the scene
   * kept. */
  char scene_file[600], link_file[600];
  snprintf(scene_file, sizeof scene_file, "%s/anim.json", dir);
  snprintf(link_file, sizeof link_file, "%s/g2.png", dir);
  assert_int_equal(symlink(scene_file, link_file), 0);
  EXPECT_USAGE_ERROR_KEEPING("frame 2: g2.png: that is the scene file "
                             "anim.json; no frame was written",
                             "render", "anim.json", "--frames", "1-3", "-o",
                             "g%d.png");
  assert_false(exists("g1.png"));
  assert_int_equal(remove_in_folder("g2.png"), 0);
  long n_anim;
  char *anim = file_bytes("anim.json", &n_anim);
  assert_true(n_anim == (long)strlen(orbit_scene) &&
              memcmp(anim, orbit_scene, (size_t)n_anim) == 0);
  free(anim);
  /* Folders after the number's that climb out of it would put every frame
   * in one file (x%d/y/.. does not). */
  EXPECT_USAGE_ERROR_KEEPING("-o x%d/y/../../f.png: the '..' after the "
                             "number's folder would put every frame in one "
                             "file",
                             "render", "anim.json", "--frames", "1-2", "-o",
                             "x%d/y/../../f.png");
  assert_false(exists("x1"));
  assert_int_equal(run("render", "anim.json", "--frames", "1-2", "-o",
                       "x%d/y/../f.png", "-q", NULL),
                   0);
  assert_true(exists("x1/f.png") && exists("x2/f.png"));
  char rm_x[700];
  snprintf(rm_x, sizeof rm_x, "rm -r '%s/x1' '%s/x2'", dir, dir);
  assert_int_equal(system(rm_x), 0);

  /* --resume keeps the frames there (here f02.png a stand-in: the still
   * image, of the frame's size) and renders the rest, and again what is
   * not an image of the frame's size (it kept any file that was not
   * empty). */
  long nstill;
  char *still_png = file_bytes("still.png", &nstill);
  char f02[600];
  snprintf(f02, sizeof f02, "%s/f02.png", dir);
  FILE *stand_in = fopen(f02, "wb");
  assert_non_null(stand_in);
  assert_int_equal(fwrite(still_png, 1, (size_t)nstill, stand_in), nstill);
  fclose(stand_in);
  put_text("f03.png", "junk");
  assert_int_equal(run("render", "anim.json", "--frames", "1-4", "-o",
                       "f%02d.png", "--resume", NULL),
                   0);
  assert_non_null(strstr(out, "frame 2: f02.png is there, kept (--resume)"));
  assert_non_null(strstr(err, "frame 3: f03.png: not a PNG file"));
  assert_non_null(strstr(err, "not a finished 32x24 frame: rendered again"));
  assert_non_null(strstr(out, "2 frames written, 2 kept (--resume)"));
  long n02;
  char *kept = file_bytes("f02.png", &n02);
  assert_true(n02 == nstill && memcmp(kept, still_png, (size_t)nstill) == 0);
  free(kept);
  free(still_png);
  assert_true(exists("f04.png"));
  /* At another size, every frame is rendered again. */
  assert_int_equal(run("render", "anim.json", "--frames", "1-2", "-o",
                       "f%02d.png", "--resume", "-W", "16", "-H", "12", "-q",
                       NULL),
                   0);
  assert_non_null(strstr(err, "frame 2: f02.png: a 32x24 image, not a "
                              "finished 16x12 frame: rendered again"));

  /* The mistakes, with the scene beside the (then empty) test folder: an
   * error writes nothing. */
  char cmd[768], scene_path[300];
  snprintf(scene_path, sizeof scene_path, "%s-anim.json", dir);
  snprintf(
      cmd, sizeof cmd,
      "cd '%s' && mv anim.json '%s' && rm -rf f0*.png "
      "out0048.png anim0007.png still.png still.json sub in3 100%%0003.png "
      "p%%3.png",
      dir, scene_path);
  assert_int_equal(system(cmd), 0);
  EXPECT_USAGE_ERROR("-anim.json's animation has frames 1-48", "render",
                     scene_path, "--frames", "40-60");
  EXPECT_USAGE_ERROR("whitted has no animation", "render", "whitted",
                     "--frames", "1");
  EXPECT_USAGE_ERROR("a frame pattern takes one number, not 2", "render",
                     scene_path, "--frames", "1", "-o", "x%d%d.png");
  EXPECT_USAGE_ERROR("a frame pattern takes one %d", "render", scene_path,
                     "--frames", "1", "-o", "x%s.png");
  EXPECT_USAGE_ERROR("a frame number's width is at most 9 (%09d)", "render",
                     scene_path, "--frames", "1", "-o", "x%10d.png");
  EXPECT_USAGE_ERROR("--frames writes .png, .bmp or .ppm", "render", scene_path,
                     "--frames", "1", "-o", "x.exr");
  EXPECT_USAGE_ERROR("--frames: '3-1' runs backwards", "render", scene_path,
                     "--frames", "3-1");
  EXPECT_USAGE_ERROR("--frames: '3-x' is not a frame", "render", scene_path,
                     "--frames", "3-x");
  EXPECT_USAGE_ERROR("--resume applies to --frames", "render", scene_path,
                     "--resume");
  EXPECT_USAGE_ERROR("--stats applies to one image", "render", scene_path,
                     "--frames", "1", "--stats");
  EXPECT_USAGE_ERROR("-o - is one stream", "render", scene_path, "--frames",
                     "1", "-o", "-");
  unlink(scene_path);
}

/* --resume checks, before any frame is written, that a frame it renders
 * again (here one of another size) can be written: a read-only f02.png of
 * the wrong size stopped the run after f01.png was written. Run as a user
 * that may not write it (root writes anything: it drops to nobody). */
static void resume_checks_the_frames_it_renders_again(void **state) {
  (void)state;
  put_text("anim.json", orbit_scene);
  assert_int_equal(run("render", "anim.json", "--frames", "2", "-o",
                       "f%02d.png", "-W", "16", "-H", "12", "-q", NULL),
                   0);
  char f02[600];
  snprintf(f02, sizeof f02, "%s/f02.png", dir);
  assert_int_equal(chmod(f02, 0444), 0);
  assert_int_equal(chmod(dir, 0777), 0);
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    int null = open("/dev/null", O_WRONLY);
    if ((geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0)) ||
        chdir(dir) != 0 || null < 0 || dup2(null, 1) < 0 || dup2(null, 2) < 0)
      _exit(97);
    execl(GLINT_EXE, "glint", "render", "anim.json", "--frames", "1-3", "-o",
          "f%02d.png", "--resume", (char *)NULL);
    _exit(98);
  }
  int status;
  assert_int_equal(waitpid(pid, &status, 0), pid);
  assert_int_equal(chmod(dir, 0700), 0);
  assert_true(WIFEXITED(status));
  if (WEXITSTATUS(status) == 98 || WEXITSTATUS(status) == 97) {
    print_message("glint cannot run as another user here\n");
    chmod(f02, 0644);
    remove_in_folder("f02.png");
    remove_in_folder("anim.json");
    skip();
  }
  assert_int_equal(WEXITSTATUS(status), 2);
  assert_false(exists("f01.png")); /* no frame was written */
  assert_int_equal(chmod(f02, 0644), 0);
  assert_int_equal(remove_in_folder("f02.png"), 0);
  assert_int_equal(remove_in_folder("anim.json"), 0);
  assert_true(folder_is_empty());
}

/* Objects that move: frame 1 (t = 1 s) of a sphere sliding 2 units in 2 s
 * is the still scene with the sphere 1 unit along, byte for byte; the
 * still render of the animated scene is its first frame. */
static void frames_with_moving_objects(void **state) {
  (void)state;
  static const char head[] =
      "{\"camera\": {\"from\": [0, 2, 6], \"at\": [0, 1, 0]},"
      " \"image\": {\"width\": 40, \"height\": 30},"
      " \"lights\": [{\"position\": [-4, 8, 6], \"color\": [1, 1, 1]}],"
      " \"materials\": {\"m\": {\"color\": [0.9, 0.2, 0.2], \"ks\": 0.3}},"
      " \"objects\": [{\"type\": \"plane\", \"point\": [0, 0, 0], "
      "\"normal\": [0, 1, 0], \"material\": \"m\"},";
  char text[2048];
  snprintf(text, sizeof text,
           "%s {\"type\": \"sphere\", \"center\": [0, 1, 0], \"radius\": 1, "
           "\"material\": \"m\", \"transform\": {\"keys\": [{\"time\": 0}, "
           "{\"time\": 2, \"translate\": [2, 0, 0]}]}}],"
           " \"animation\": {\"fps\": 1, \"frames\": [0, 2]}}",
           head);
  put_text("move.json", text);
  snprintf(text, sizeof text,
           "%s {\"type\": \"sphere\", \"center\": [1, 1, 0], \"radius\": 1, "
           "\"material\": \"m\"}]}",
           head);
  put_text("moved.json", text);
  assert_int_equal(run("render", "move.json", "--frames", "0-2", "-o",
                       "m%d.png", "-q", NULL),
                   0);
  assert_int_equal(run("render", "moved.json", "-o", "moved.png", "-q", NULL),
                   0);
  assert_int_equal(run("render", "move.json", "-o", "still.png", "-q", NULL),
                   0);
  const char *same[][2] = {{"m1.png", "moved.png"}, {"m0.png", "still.png"}};
  for (int i = 0; i < 2; i++) {
    long na, nb;
    char *a = file_bytes(same[i][0], &na), *b = file_bytes(same[i][1], &nb);
    if (na != nb || memcmp(a, b, (size_t)na) != 0)
      fail_msg("%s differs from %s", same[i][0], same[i][1]);
    free(a);
    free(b);
  }
  char cmd[512];
  snprintf(cmd, sizeof cmd,
           "cd '%s' && rm -f m0.png m1.png m2.png moved.png "
           "still.png move.json moved.json",
           dir);
  assert_int_equal(system(cmd), 0);
  /* A spline that overshoots between valid keys (the scale below 0 at
   * frame 1 of 0-3) is found before any frame is written: frame 0's file
   * keeps what it held. */
  snprintf(text, sizeof text,
           "%s {\"type\": \"sphere\", \"center\": [0, 1, 0], \"radius\": 1, "
           "\"material\": \"m\", \"transform\": {\"interpolation\": "
           "\"catmull-rom\", \"keys\": [{\"time\": 0, \"scale\": 0.001}, "
           "{\"time\": 1, \"scale\": 0.001}, {\"time\": 1.01, \"scale\": "
           "1}]}}], \"animation\": {\"fps\": 3, \"frames\": [0, 3]}}",
           head);
  put_text("overshoot.json", text);
  put_text("o0.png", "precious");
  EXPECT_USAGE_ERROR_KEEPING(
      "overshoot.json: frame 1 (t = 0.333333 s): object 1's motion at "
      "0.333333 s has a scale of",
      "render", "overshoot.json", "--frames", "0-3", "-o", "o%d.png");
  /* A translation overshooting past 1e15 is named as such (it was
   * reported as "a scale of 1"). */
  snprintf(text, sizeof text,
           "%s {\"type\": \"sphere\", \"center\": [0, 1, 0], \"radius\": 1, "
           "\"material\": \"m\", \"transform\": {\"interpolation\": "
           "\"catmull-rom\", \"keys\": [{\"time\": 0, \"translate\": [0, 0, "
           "0]}, {\"time\": 1, \"translate\": [1e15, 0, 0]}, {\"time\": 2, "
           "\"translate\": [1e15, 0, 0]}]}}], \"animation\": {\"fps\": 4, "
           "\"frames\": [0, 8]}}",
           head);
  put_text("overshoot.json", text);
  EXPECT_USAGE_ERROR_KEEPING(
      "overshoot.json: frame 5 (t = 1.25 s): object 1's motion at 1.25 s has "
      "a translate beyond magnitude 1e15",
      "render", "overshoot.json", "--frames", "0-8", "-o", "o%d.png");
  long n;
  char *kept = file_bytes("o0.png", &n);
  assert_true(n == 8 && memcmp(kept, "precious", 8) == 0);
  free(kept);
  snprintf(cmd, sizeof cmd, "cd '%s' && rm -f o0.png overshoot.json", dir);
  assert_int_equal(system(cmd), 0);
  assert_true(folder_is_empty());
}

/* Runs `glint render ARGS... -o keep.png` over an existing keep.png, sends
 * `sig` half a second in, and waits (at most 30 s: then it hangs, and
 * fails). Returns the exit status, with stderr in `err` and the tenths of
 * a second it took to end in `*tenths`; keep.png must be untouched and no
 * temporary file left. */
static int interrupt_render(const char *const *args, int sig, int *tenths) {
  char p[128], err_path[128];
  snprintf(p, sizeof p, "%s/keep.png", dir);
  snprintf(err_path, sizeof err_path, "%s/.stderr", dir);
  FILE *f = fopen(p, "wb");
  fputs("precious", f);
  fclose(f);
  const char *argv[32] = {GLINT_EXE, "render"};
  int n = 2;
  while (*args && n < 28)
    argv[n++] = *args++;
  argv[n++] = "-o";
  argv[n++] = p;
  argv[n] = NULL;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 2, err_path,
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid;
  assert_int_equal(
      posix_spawn(&pid, GLINT_EXE, &fa, NULL, (char *const *)argv, environ), 0);
  posix_spawn_file_actions_destroy(&fa);
  usleep(500 * 1000); /* well into the render, minutes from its end */
  kill(pid, sig);
  int status = 0;
  *tenths = 0;
  while (waitpid(pid, &status, WNOHANG) == 0 && *tenths < 300) {
    usleep(100 * 1000);
    ++*tenths;
  }
  if (*tenths == 300) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    fail_msg("glint render went on 30 s after signal %d", sig);
  }
  slurp(err_path, err, sizeof err);
  unlink(err_path);
  assert_true(WIFEXITED(status));
  char buf[32];
  slurp(p, buf, sizeof buf);
  assert_string_equal(buf, "precious");
  unlink(p);
  assert_true(folder_is_empty()); /* no temporary file left */
  return WEXITSTATUS(status);
}

/* Ctrl-C: a message, status 130, the existing file untouched. */
static void interrupt_keeps_the_old_file(void **state) {
  (void)state;
  const char *args[] = {"billiard", "-d",   "64", "-s",   "4096",
                        "-W",       "1024", "-H", "1024", NULL};
  int tenths;
  assert_int_equal(interrupt_render(args, SIGINT, &tenths), 130);
  assert_non_null(strstr(err, "glint: interrupted;"));
  /* An alarm from outside stops it as SIGTERM would (it was taken for the
   * grace's own alarm: "did not stop within 2 s", at once). */
  assert_int_equal(interrupt_render(args, SIGALRM, &tenths), 130);
  assert_non_null(strstr(err, "glint: interrupted; "));
  assert_non_null(strstr(err, "keep.png was not written"));
  assert_null(strstr(err, "within"));
}

/* A stop signal during a render whose tiles take far longer than anyone
 * waits: the process ends STOP_GRACE (2) seconds later, says so, exits 130
 * and leaves the old file and no temporary one. The render: three nested
 * spheres that reflect and transmit everything (kr = kt = 1), so that no
 * ray's weight falls and faint rays never end the tree (specification §4):
 * the rays nearly double at every level, and at depth 60 one 16x16 tile
 * would take longer than the universe has existed. */
static void an_endless_render_stops_within_the_grace(void **state) {
  (void)state;
  char scene[300];
  snprintf(scene, sizeof scene, "%s-endless.nff", dir);
  FILE *f = fopen(scene, "w");
  assert_non_null(f);
  fputs("v\nfrom 0 0 -3\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.001\n"
        "resolution 64 64\nb 0.2 0.3 0.5\nl 5 5 -5\n"
        "f 1 1 1 0 1 10 1 1.5\ns 0 0 0 1\ns 0 0 0 0.6\ns 0 0 0 0.3\n",
        f);
  fclose(f);
  const char *args[] = {scene,          "-d", "60", "-b",
                        "scalar-float", "-t", "1",  NULL};
  int tenths;
  int status = interrupt_render(args, SIGTERM, &tenths);
  unlink(scene);
  assert_int_equal(status, 130);
  assert_true(tenths >= 15); /* the grace, not an early end */
  assert_non_null(strstr(err, "did not stop within 2 s"));
}

/* Ctrl-C during bench --time-to-image: exit 130, said so, and the folder
 * of its images removed (it was left in TMPDIR). */
static void interrupted_time_to_image_leaves_nothing(void **state) {
  (void)state;
  char tmp[600], env_tmp[640], err_path[600];
  snprintf(tmp, sizeof tmp, "%s/tmp", dir);
  snprintf(env_tmp, sizeof env_tmp, "TMPDIR=%s", tmp);
  snprintf(err_path, sizeof err_path, "%s/.stderr", dir);
  assert_int_equal(mkdir(tmp, 0755), 0);
  char *argv[] = {"glint",    "bench",    "--time-to-image",
                  "--scenes", "billiard", "--runs",
                  "255",      "-s",       "16",
                  "-t",       "1",        NULL};
  char *envp[] = {env_tmp, NULL};
  pid_t pid = spawn_glint(argv, envp, "/dev/null", err_path);
  usleep(500 * 1000); /* minutes from the end of 255 runs at 16 spp */
  kill(pid, SIGINT);
  int status;
  assert_int_equal(waitpid(pid, &status, 0), pid);
  slurp(err_path, err, sizeof err);
  unlink(err_path);
  assert_true(WIFEXITED(status));
  assert_int_equal(WEXITSTATUS(status), 130);
  assert_non_null(strstr(err, "interrupted: billiard"));
  assert_int_equal(rmdir(tmp), 0); /* empty: the images' folder is gone */
  assert_true(folder_is_empty());
}

/* Whether process `pid` has a file open in the test's folder (readlink of
 * /proc/PID/fd: "/dir/#123 (deleted)" for an unnamed one). */
static int writes_in_folder(pid_t pid) {
  char fds[32], link[64], to[700];
  snprintf(fds, sizeof fds, "/proc/%d/fd", (int)pid);
  DIR *d = opendir(fds);
  if (!d)
    return 0;
  int found = 0;
  for (struct dirent *e; !found && (e = readdir(d));) {
    snprintf(link, sizeof link, "%s/%.16s", fds, e->d_name);
    ssize_t n = readlink(link, to, sizeof to - 1);
    if (n > 0) {
      to[n] = 0;
      found = strncmp(to, dir, strlen(dir)) == 0 && to[strlen(dir)] == '/';
    }
  }
  closedir(d);
  return found;
}

/* A stop signal that glint was started with ignored (nohup's SIGHUP)
 * stays ignored, as a shell leaves it: glint now handles SIGHUP from its
 * start, and ended on it. SIGTERM still stops the render. */
static void ignored_stop_signals_stay_ignored(void **state) {
  (void)state;
  char out_path[600], err_path[600];
  snprintf(out_path, sizeof out_path, "%s/never.png", dir);
  snprintf(err_path, sizeof err_path, "%s/.stderr", dir);
  char *argv[] = {"glint", "render", "billiard", "-d",     "64",
                  "-s",    "4096",   "-W",       "1024",   "-H",
                  "1024",  "-q",     "-o",       out_path, NULL};
  struct sigaction ignore, saved;
  memset(&ignore, 0, sizeof ignore);
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGHUP, &ignore, &saved);
  pid_t pid = spawn_glint(argv, environ, "/dev/null", err_path);
  sigaction(SIGHUP, &saved, NULL);
  usleep(200 * 1000);
  kill(pid, SIGHUP);
  usleep(500 * 1000);
  int status;
  pid_t ended = waitpid(pid, &status, WNOHANG);
  kill(pid, SIGTERM);
  if (ended == 0)
    assert_int_equal(waitpid(pid, &status, 0), pid);
  slurp(err_path, err, sizeof err);
  unlink(err_path);
  assert_int_equal(ended, 0); /* still rendering after SIGHUP */
  assert_true(WIFEXITED(status));
  assert_int_equal(WEXITSTATUS(status), 130);
  assert_false(exists("never.png"));
  assert_true(folder_is_empty());
}

/* The CPU time `pid` has used, in clock ticks; -1 where /proc cannot say. */
static long cpu_ticks(pid_t pid) {
  char path[64], text[1024];
  snprintf(path, sizeof path, "/proc/%d/stat", (int)pid);
  FILE *f = fopen(path, "r");
  if (!f)
    return -1;
  size_t n = fread(text, 1, sizeof text - 1, f);
  fclose(f);
  text[n] = '\0';
  const char *after_name = strrchr(text, ')'); /* the name may hold spaces */
  unsigned long user, system;
  if (!after_name || sscanf(after_name + 2,
                            "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u "
                            "%lu %lu",
                            &user, &system) != 2)
    return -1;
  return (long)(user + system);
}

/* A stop signal while the scene loads (nothing cancels a load) ends glint
 * with a message and status 130, and nothing written: its default action
 * ended glint without a word. The scene, a million spheres, takes 0.4 s to
 * read here (and then 1 s to prepare); the signal comes after a tenth of a
 * second of CPU time, once glint is surely running. */
static void stopped_while_loading(void **state) {
  (void)state;
  if (cpu_ticks(getpid()) < 0)
    skip();
  char scene[600], output[600], err_path[600];
  snprintf(scene, sizeof scene, "%s/many.nff", dir);
  snprintf(output, sizeof output, "%s/out.png", dir);
  snprintf(err_path, sizeof err_path, "%s/.stderr", dir);
  FILE *f = fopen(scene, "w");
  assert_non_null(f);
  fputs(small_nff, f);
  for (int i = 0; i < 1000000; i++)
    fprintf(f, "s %d %d %d 0.1\n", i % 100, i / 100 % 100, i / 10000);
  assert_int_equal(fclose(f), 0);
  const long ticks = sysconf(_SC_CLK_TCK) / 10;
  const int signals[] = {SIGINT, SIGTERM, SIGHUP};
  for (int k = 0; k < 3; k++) {
    char *argv[] = {"glint", "render", scene, "-q", "-o", output, NULL};
    pid_t pid = spawn_glint(argv, environ, "/dev/null", err_path);
    for (int tries = 0; cpu_ticks(pid) < ticks && tries < 30000; tries++)
      usleep(1000);
    kill(pid, signals[k]);
    assert_int_equal(exit_status(pid, err_path), 130);
    /* "glint: interrupted (SIGINT)" while loading, as it should be; the
     * render's own message should the load have ended */
    assert_int_equal(strncmp(err, "glint: interrupted", 18), 0);
    assert_false(exists("out.png"));
  }
  unlink(scene);
  assert_true(folder_is_empty());
}

/* A stop signal during --frames, while the frames' files are checked or
 * while the frames render, takes away the folders the run made that hold
 * no frame (-o o/%d/f.png makes a folder a frame: a Ctrl-C left 26 000
 * empty ones); those holding a frame stay. */
static void stopped_frames_leave_no_empty_folders(void **state) {
  (void)state;
  if (cpu_ticks(getpid()) < 0)
    skip();
  char text[2048], scene[600], pattern[600], err_path[600];
  const char *frames = strstr(orbit_scene, "[1, 48]");
  snprintf(text, sizeof text, "%.*s[1, 20000]%s", (int)(frames - orbit_scene),
           orbit_scene, frames + 7);
  put_text("long.json", text);
  snprintf(scene, sizeof scene, "%s/long.json", dir);
  snprintf(pattern, sizeof pattern, "%s/o/%%d/f.png", dir);
  snprintf(err_path, sizeof err_path, "%s/.stderr", dir);
  const long ticks = sysconf(_SC_CLK_TCK) / 5;
  char *argv[] = {"glint", "render", scene, "--frames", "1-20000", "-s",
                  "16",    "-q",     "-o",  pattern,    NULL};
  pid_t pid = spawn_glint(argv, environ, "/dev/null", err_path);
  for (int tries = 0; cpu_ticks(pid) < ticks && tries < 30000; tries++)
    usleep(1000);
  kill(pid, SIGTERM);
  assert_int_equal(exit_status(pid, err_path), 130);
  assert_non_null(strstr(err, "glint: interrupted"));
  char o[600];
  snprintf(o, sizeof o, "%s/o", dir);
  DIR *d = opendir(o);
  int empty = 0;
  for (struct dirent *e; d && (e = readdir(d));) {
    if (e->d_name[0] == '.')
      continue;
    char frame[1200];
    snprintf(frame, sizeof frame, "%s/%s/f.png", o, e->d_name);
    empty += access(frame, F_OK) != 0;
  }
  if (d)
    closedir(d);
  assert_int_equal(empty, 0);
  char cmd[1300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s' '%s'", o, scene);
  assert_int_equal(system(cmd), 0);
  assert_true(folder_is_empty());
}

/* Ctrl-C while --resume reads the frames already written (milliseconds
 * each: about 10 s for 3 000 of 640x480) stops there: it was noticed only
 * at the next frame rendered, and with every frame kept not at all (exit
 * 0, "0 frames written, 3000 kept"). */
static void stopped_while_resuming(void **state) {
  (void)state;
  if (cpu_ticks(getpid()) < 0)
    skip();
  char text[2048], scene[600], pattern[600], err_path[600], first[600];
  const char *frames = strstr(orbit_scene, "[1, 48]");
  snprintf(text, sizeof text, "%.*s[1, 3000]%s", (int)(frames - orbit_scene),
           orbit_scene, frames + 7);
  put_text("kept.json", text);
  snprintf(scene, sizeof scene, "%s/kept.json", dir);
  assert_int_equal(run("render", "kept.json", "--frames", "1", "-W", "640",
                       "-H", "480", "-s", "1", "-q", "-o", "k/f%d.png", NULL),
                   0);
  snprintf(first, sizeof first, "%s/k/f1.png", dir);
  for (int f = 2; f <= 3000; f++) {
    char name[700];
    snprintf(name, sizeof name, "%s/k/f%d.png", dir, f);
    assert_int_equal(link(first, name), 0);
  }
  snprintf(pattern, sizeof pattern, "%s/k/f%%d.png", dir);
  snprintf(err_path, sizeof err_path, "%s/.stderr", dir);
  /* 1.5 s of the CPU: past the checks of the frames and their files
   * (under a second with sanitizers), inside the 10 s or more of reading */
  const long ticks = 3 * sysconf(_SC_CLK_TCK) / 2;
  char *argv[] = {"glint", "render", scene,   "--frames", "1-3000", "-W",
                  "640",   "-H",     "480",   "-s",       "1",      "--resume",
                  "-q",    "-o",     pattern, NULL};
  pid_t pid = spawn_glint(argv, environ, "/dev/null", err_path);
  for (int tries = 0; cpu_ticks(pid) < ticks && tries < 30000; tries++)
    usleep(1000);
  kill(pid, SIGTERM);
  assert_int_equal(exit_status(pid, err_path), 130);
  const char *at = strstr(err, "glint: interrupted before frame ");
  assert_non_null(at);
  int frame = atoi(at + strlen("glint: interrupted before frame "));
  assert_true(frame > 1 && frame < 3000); /* it stopped among the reads */
  char cmd[1300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s/k' '%s'", dir, scene);
  assert_int_equal(system(cmd), 0);
  assert_true(folder_is_empty());
}

/* A render killed outright (SIGKILL, the out-of-memory killer, a batch
 * system's hard stop) has no handler to run, and still leaves nothing
 * behind: the image being written has no name until it is complete. */
static void a_killed_render_leaves_no_file(void **state) {
  (void)state;
  int probe = open(dir, O_TMPFILE | O_WRONLY, 0600);
  if (probe < 0)
    skip(); /* this folder's file system has no unnamed files */
  close(probe);
  char keep[600];
  snprintf(keep, sizeof keep, "%s/keep.png", dir);
  put_text("keep.png", "precious");
  char *argv[] = {"glint", "render", "billiard", "-d", "64", "-s", "4096", "-W",
                  "1024",  "-H",     "1024",     "-q", "-o", keep, NULL};
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid;
  assert_int_equal(posix_spawn(&pid, GLINT_EXE, &fa, NULL, argv, environ), 0);
  posix_spawn_file_actions_destroy(&fa);
  int tenths = 0; /* until the image file is open, at most 30 s */
  while (!writes_in_folder(pid) && tenths++ < 300)
    usleep(100 * 1000);
  kill(pid, SIGKILL);
  int status;
  assert_int_equal(waitpid(pid, &status, 0), pid);
  assert_true(tenths < 300);
  assert_true(WIFSIGNALED(status));
  char buf[32];
  slurp(keep, buf, sizeof buf);
  assert_string_equal(buf, "precious");
  unlink(keep);
  assert_true(folder_is_empty()); /* no temporary file */
}

/* Scenes whose names share their first 63 characters are two scenes in
 * bench's tables and CSV (their names were cut to 63: one row name for
 * both, and one plot replaced the other's). */
static void bench_keeps_long_scene_names(void **state) {
  (void)state;
  char a[128], b[128], list[300];
  memset(a, 'p', 70);
  memcpy(a + 70, "_one.nff", 9);
  memset(b, 'p', 70);
  memcpy(b + 70, "_two.nff", 9);
  put_text(a, small_nff);
  put_text(b, small_nff);
  snprintf(list, sizeof list, "%s,%s", a, b);
  assert_int_equal(run("bench", "--scenes", list, "--depths", "1", "--runs",
                       "1", "-s", "1", "--backends", "scalar-float", "--csv",
                       "long.csv", NULL),
                   0);
  long n;
  char *csv = file_bytes("long.csv", &n);
  a[74] = b[74] = '\0'; /* the stems */
  assert_non_null(strstr(csv, a));
  assert_non_null(strstr(csv, b));
  free(csv);
  remove_in_folder("long.csv");
  a[74] = b[74] = '.';
  /* A CSV of a legal 254-byte name (its temporary file's suffix made the
   * name too long) */
  char csv_name[255];
  memset(csv_name, 'c', 250);
  memcpy(csv_name + 250, ".csv", 5);
  assert_int_equal(run("bench", "--scenes", a, "--depths", "1", "--runs", "1",
                       "-s", "1", "--backends", "scalar-float", "--csv",
                       csv_name, NULL),
                   0);
  assert_true(exists(csv_name));
  remove_in_folder(csv_name);
  remove_in_folder(a);
  remove_in_folder(b);
}

static void compare_threshold_and_difference(void **state) {
  (void)state;
  assert_int_equal(
      run("render", "-W", "16", "-H", "12", "-q", "-o", "a.png", NULL), 0);
  assert_int_equal(run("render", "-W", "16", "-H", "12", "-q", "-d", "1", "-o",
                       "b.png", NULL),
                   0);
  assert_int_equal(run("compare", "a.png", "a.png", "--min-psnr", "99", NULL),
                   0);
  assert_non_null(strstr(out, "inf"));
  assert_int_equal(run("compare", "a.png", "b.png", "--min-psnr", "99",
                       "--diff", "d.ppm", NULL),
                   1);
  assert_non_null(strstr(err, "is below --min-psnr 99"));
  assert_true(exists("d.ppm"));
  assert_int_equal(run("compare", "a.png", "b.png", "--min-psnr", "1", NULL),
                   0);
  /* (the folder holds the images now: no EXPECT_USAGE_ERROR) */
  assert_int_equal(run("compare", "a.png", "missing.png", NULL), 2);
  assert_non_null(strstr(err, "glint: missing.png: No such file"));
  char folder[600];
  snprintf(folder, sizeof folder, "%s/folder.png", dir);
  assert_int_equal(mkdir(folder, 0755), 0);
  assert_int_equal(run("compare", "a.png", "folder.png", NULL), 2);
  assert_non_null(strstr(err, "glint: folder.png: a folder, not an image"));
  assert_int_equal(rmdir(folder), 0);
  assert_int_equal(run("compare", "a.png", "b.png", "--min-psnr", "x", NULL),
                   2);
  assert_non_null(strstr(err, "--min-psnr: 'x' is not a number"));
  /* inf, as compare prints it: identical images only (it was "not a
   * number"); a number past double's range is named as such */
  assert_int_equal(run("compare", "a.png", "a.png", "--min-psnr", "inf", NULL),
                   0);
  assert_int_equal(run("compare", "a.png", "b.png", "--min-psnr", "inf", NULL),
                   1);
  assert_non_null(strstr(err, "is below --min-psnr inf"));
  /* A PSNR just below the threshold is shown with the decimals that tell
   * them apart (29.999998 was "PSNR 30.00 dB is below --min-psnr 30"):
   * 1000x1 grey 100 against 2408 samples 109, one 105, three 101. */
  static unsigned char near[2][3000];
  memset(near, 100, sizeof near);
  memset(near[1], 109, 2408);
  near[1][2408] = 105;
  memset(near[1] + 2409, 101, 3);
  for (int k = 0; k < 2; k++) {
    char name[600];
    snprintf(name, sizeof name, "%s/near%d.ppm", dir, k);
    FILE *f = fopen(name, "wb");
    assert_non_null(f);
    fputs("P6\n1000 1\n255\n", f);
    assert_int_equal(fwrite(near[k], 1, 3000, f), 3000);
    assert_int_equal(fclose(f), 0);
  }
  assert_int_equal(
      run("compare", "near0.ppm", "near1.ppm", "--min-psnr", "30", NULL), 1);
  assert_non_null(strstr(out, "PSNR 30.00 dB"));
  assert_non_null(strstr(err, "PSNR 29.99998 dB is below --min-psnr 30.00000"));
  assert_int_equal(
      run("compare", "a.png", "b.png", "--min-psnr", "1e999", NULL), 2);
  assert_non_null(strstr(err, "--min-psnr: '1e999' is not a finite number"));
  assert_int_equal(run("compare", "a.png", "b.png", "a.png", NULL), 2);
  assert_non_null(strstr(err, "compare takes two images"));
  /* Sizes are compared from the headers, before either image is decoded:
   * this one, 16384 x 16384, was read (805 MB) before the sizes were
   * compared, and found short. */
  char huge[600];
  snprintf(huge, sizeof huge, "%s/huge.ppm", dir);
  FILE *hf = fopen(huge, "wb");
  assert_non_null(hf);
  fputs("P6\n16384 16384\n255\nabc", hf);
  fclose(hf);
  assert_int_equal(run("compare", "huge.ppm", "a.png", NULL), 2);
  assert_non_null(strstr(err, "huge.ppm is 16384x16384 but a.png is 16x12"));
  /* A --diff that cannot be written fails before the comparison. */
  assert_int_equal(
      run("compare", "a.png", "b.png", "--diff", "no/such/d.png", NULL), 2);
  assert_non_null(strstr(err, "no/such/d.png: cannot write here"));
  assert_string_equal(out, "");
  /* ...and so does a --diff that is one of the images, by name or through
   * a link (it was overwritten by the difference). */
  long before_n, after_n;
  char *before = file_bytes("a.png", &before_n);
  EXPECT_USAGE_ERROR_KEEPING("--diff a.png: that is a.png, an image being "
                             "compared",
                             "compare", "a.png", "b.png", "--diff", "a.png");
  char link_path[600];
  snprintf(link_path, sizeof link_path, "%s/link.png", dir);
  char target[600];
  snprintf(target, sizeof target, "%s/a.png", dir);
  assert_int_equal(symlink(target, link_path), 0);
  EXPECT_USAGE_ERROR_KEEPING("--diff link.png: that is a.png, an image being "
                             "compared",
                             "compare", "b.png", "a.png", "--diff", "link.png");
  char *after = file_bytes("a.png", &after_n);
  assert_true(before_n == after_n && memcmp(before, after, before_n) == 0);
  free(before);
  free(after);
  assert_int_equal(remove_in_folder("link.png"), 0);
  /* ...and a --diff through a link to a scene file, as render's -o (the
   * scene was replaced by the difference image). */
  put_text("s.json", "{}");
  snprintf(target, sizeof target, "%s/s.json", dir);
  assert_int_equal(symlink(target, link_path), 0);
  EXPECT_USAGE_ERROR_KEEPING("a scene or mesh file", "compare", "a.png",
                             "b.png", "--diff", "link.png");
  char *scene = file_bytes("s.json", &after_n);
  assert_true(after_n == 2 && memcmp(scene, "{}", 2) == 0);
  free(scene);
  assert_int_equal(remove_in_folder("link.png"), 0);
  assert_int_equal(remove_in_folder("s.json"), 0);
  char cmd[256];
  snprintf(cmd, sizeof cmd, "rm -f '%s'/*.png '%s'/*.ppm", dir, dir);
  assert_int_equal(system(cmd), 0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(usage_errors),
      cmocka_unit_test(size_errors),
      cmocka_unit_test(output_errors),
      cmocka_unit_test(existing_file_survives_errors),
      cmocka_unit_test(help_and_version),
      cmocka_unit_test(render_writes_every_format),
      cmocka_unit_test(render_writes_the_film),
      cmocka_unit_test(png_compression_and_gamma),
      cmocka_unit_test(defaults_quiet_and_stats),
      cmocka_unit_test(a_far_object_is_noted),
      cmocka_unit_test(bench_runs_and_writes_csv),
      cmocka_unit_test(bench_reuses_a_renderer_per_column),
      cmocka_unit_test(bench_auto_renders_what_render_chooses),
      cmocka_unit_test(bench_csv_keeps_files_on_error),
      cmocka_unit_test(output_linked_to_the_scene),
      cmocka_unit_test(default_output_is_named_after_the_scene),
      cmocka_unit_test(bench_modes_and_their_files),
      cmocka_unit_test(bench_time_to_image),
      cmocka_unit_test(bench_errors),
      cmocka_unit_test(a_closed_pipe_is_an_error),
      cmocka_unit_test(a_full_standard_output_is_an_error),
      cmocka_unit_test(closed_standard_streams),
      cmocka_unit_test(resume_checks_the_frames_it_renders_again),
      cmocka_unit_test(a_file_past_the_size_limit_is_an_error),
      cmocka_unit_test(a_plot_past_the_size_limit_is_an_error),
      cmocka_unit_test(a_small_stack_limit),
      cmocka_unit_test(written_files_keep_their_permissions),
      cmocka_unit_test(out_of_memory_exits_1),
      cmocka_unit_test(bench_plot_names_are_not_commands),
      cmocka_unit_test(bench_thread_columns),
      cmocka_unit_test(missing_instruction_sets),
      cmocka_unit_test(options_as_people_write_them),
      cmocka_unit_test(default_threads_follow_the_affinity),
      cmocka_unit_test(frames_of_an_animation),
      cmocka_unit_test(stopped_frames_leave_no_empty_folders),
      cmocka_unit_test(stopped_while_resuming),
      cmocka_unit_test(frames_with_moving_objects),
      cmocka_unit_test(interrupt_keeps_the_old_file),
      cmocka_unit_test(an_endless_render_stops_within_the_grace),
      cmocka_unit_test(interrupted_time_to_image_leaves_nothing),
      cmocka_unit_test(a_killed_render_leaves_no_file),
      cmocka_unit_test(stopped_while_loading),
      cmocka_unit_test(ignored_stop_signals_stay_ignored),
      cmocka_unit_test(compare_threshold_and_difference),
      cmocka_unit_test(bench_keeps_long_scene_names),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
