/* Threads with a stack of glint's own size. A new thread's stack is by
 * default the process's stack limit (ulimit -s), which a hostile or
 * embedded environment may set to a few KiB, and an application may call
 * glint from a thread of a small stack of its own. The deepest path through
 * the tracers, the AVX-512 beams' recursion at depth 64, needs about
 * 512 KiB. */
#ifndef GLINT_CORE_THREAD_H
#define GLINT_CORE_THREAD_H

#include <pthread.h>
#include <stddef.h>

/* The stack of glint's threads: the size Linux gives by default whatever
 * the limit (untouched stack pages cost no memory). */
#define GLI_THREAD_STACK ((size_t)8 << 20)

/* The stack a thread needs to render on: twice the deepest path. */
#define GLI_RENDER_STACK ((size_t)1 << 20)

/* pthread_create with a stack of GLI_THREAD_STACK bytes: 0, or the error
 * number. */
int gli_thread_start(pthread_t *id, void *(*run)(void *), void *arg);

/* Whether the calling thread's stack has GLI_RENDER_STACK bytes left below
 * the caller's frame (0 where that cannot be told). Costs a system call or
 * a read of /proc/self/maps: ask once per thread. */
int gli_thread_can_render(void);

#endif
