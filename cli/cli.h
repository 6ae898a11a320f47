#ifndef GLINT_CLI_CLI_H
#define GLINT_CLI_CLI_H

int cmd_render(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_compare(int argc, char **argv);

/* Loads a built-in scene by name, or a scene file when the argument names
 * one (it has a '.' or a '/'); prints one message and returns NULL on error.
 * `stem` receives the name to derive an output file from. */
struct glint_scene *cli_load_scene(const char *arg, char *stem,
                                   unsigned long stem_size);

/* Seconds on a monotonic clock, for timing stages. */
double cli_now(void);

/* Peak resident set size of this process, in MiB. */
double cli_peak_rss_mib(void);

#endif
