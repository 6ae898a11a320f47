/* A fixed pool of worker threads, started once and reused for every frame:
 * a renderer's frames cost no thread creation. The calling thread works
 * too, as worker 0, where its stack has room (gli_thread_can_render);
 * where it has not (a small thread of the application, a process run
 * under a small ulimit -s), a thread of core/thread.h, with a stack of
 * glint's own size, works in its place. */
#ifndef GLINT_RENDER_THREAD_POOL_H
#define GLINT_RENDER_THREAD_POOL_H

#include "glint.h"

typedef struct thread_pool thread_pool;

/* The work of one worker: index 0 .. workers - 1. */
typedef void (*pool_task)(void *arg, int worker);

/* Starts threads - 1 threads (fewer if the system refuses some: the pool
 * then has fewer workers, which gli_thread_pool_size tells). */
glint_status gli_thread_pool_create(int threads, thread_pool **pool,
                                    glint_error *error);
void gli_thread_pool_destroy(thread_pool *pool);
int gli_thread_pool_size(const thread_pool *pool);

/* Runs task(arg, i) for i in 0 .. workers - 1 (workers <= size), i = 0 on
 * the calling thread or its stand-in, and returns when every one has
 * returned. */
void gli_thread_pool_run(thread_pool *pool, int workers, pool_task task,
                         void *arg);

#endif
