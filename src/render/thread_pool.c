/* The thread pool of render/thread_pool.h: workers sleep on a condition
 * variable between runs; a run bumps a generation counter and wakes them,
 * and the last worker to finish wakes the caller. */
#include "render/thread_pool.h"

#include "core/error.h"
#include "core/thread.h"

#include <pthread.h>
#include <stdlib.h>

typedef struct pool_thread {
  thread_pool *pool;
  int index;
  unsigned long seen; /* the run it last saw (at its start: the current) */
  pthread_t id;
} pool_thread;

struct thread_pool {
  pthread_mutex_t lock;
  pthread_cond_t wake, done;
  unsigned long generation; /* bumped by each run */
  int quit;
  int size;         /* workers: the caller (or its stand-in) and the threads */
  int stand_in;     /* whether threads[0], worker 0's stand-in, has started */
  int first;        /* the first worker of the current run on a thread: 1 while
                       the caller works as worker 0, else 0 */
  pthread_t caller; /* the last caller, and whether it can be worker 0 */
  int caller_known, caller_can_work;
  int workers; /* of the current run */
  int pending; /* workers of the current run on threads still working */
  pool_task task;
  void *arg;
  pool_thread *threads; /* worker i's at [i] */
};

static void *thread_main(void *p) {
  pool_thread *self = p;
  thread_pool *pool = self->pool;
  unsigned long seen = self->seen;
  pthread_mutex_lock(&pool->lock);
  for (;;) {
    while (!pool->quit && pool->generation == seen)
      pthread_cond_wait(&pool->wake, &pool->lock);
    if (pool->quit)
      break;
    seen = pool->generation;
    if (self->index < pool->first || self->index >= pool->workers)
      continue;
    pool_task task = pool->task;
    void *arg = pool->arg;
    pthread_mutex_unlock(&pool->lock);
    task(arg, self->index);
    pthread_mutex_lock(&pool->lock);
    if (--pool->pending == 0)
      pthread_cond_signal(&pool->done);
  }
  pthread_mutex_unlock(&pool->lock);
  return NULL;
}

glint_status gli_thread_pool_create(int threads, thread_pool **out,
                                    glint_error *error) {
  thread_pool *pool = calloc(1, sizeof *pool);
  pool_thread *t = calloc((size_t)(threads > 1 ? threads : 1), sizeof *t);
  if (!pool || !t) {
    free(pool);
    free(t);
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  }
  pthread_mutex_init(&pool->lock, NULL);
  pthread_cond_init(&pool->wake, NULL);
  pthread_cond_init(&pool->done, NULL);
  pool->threads = t;
  pool->size = 1;
  for (int i = 1; i < threads; i++) {
    t[i].pool = pool;
    t[i].index = i;
    if (gli_thread_start(&t[i].id, thread_main, &t[i]) != 0)
      break; /* the threads that did start do all the work */
    pool->size = i + 1;
  }
  *out = pool;
  return GLINT_OK;
}

void gli_thread_pool_destroy(thread_pool *pool) {
  if (!pool)
    return;
  pthread_mutex_lock(&pool->lock);
  pool->quit = 1;
  pthread_cond_broadcast(&pool->wake);
  pthread_mutex_unlock(&pool->lock);
  for (int i = pool->stand_in ? 0 : 1; i < pool->size; i++)
    pthread_join(pool->threads[i].id, NULL);
  pthread_cond_destroy(&pool->wake);
  pthread_cond_destroy(&pool->done);
  pthread_mutex_destroy(&pool->lock);
  free(pool->threads);
  free(pool);
}

int gli_thread_pool_size(const thread_pool *pool) { return pool->size; }

void gli_thread_pool_run(thread_pool *pool, int workers, pool_task task,
                         void *arg) {
  if (workers > pool->size)
    workers = pool->size;
  /* The caller works too where its stack allows: a frame then stays on
   * the core whose caches hold the last one (a single-threaded viewer's
   * frames took 8% longer handed to a thread and back). Where it does not,
   * a thread stands in for it, started the first time it is needed (when
   * the system refuses one, the caller works whatever its stack). */
  if (!pool->caller_known || !pthread_equal(pool->caller, pthread_self())) {
    pool->caller = pthread_self();
    pool->caller_can_work = gli_thread_can_render();
    pool->caller_known = 1;
  }
  if (!pool->caller_can_work && !pool->stand_in) {
    pool_thread *t = &pool->threads[0];
    t->pool = pool;
    t->index = 0;
    t->seen = pool->generation; /* (no run is under way: runs never overlap) */
    pool->stand_in = gli_thread_start(&t->id, thread_main, t) == 0;
  }
  int first = pool->caller_can_work || !pool->stand_in ? 1 : 0;
  if (workers > first) {
    pthread_mutex_lock(&pool->lock);
    pool->task = task;
    pool->arg = arg;
    pool->first = first;
    pool->workers = workers;
    pool->pending = workers - first;
    pool->generation++;
    pthread_cond_broadcast(&pool->wake);
    pthread_mutex_unlock(&pool->lock);
  }
  if (first)
    task(arg, 0);
  if (workers > first) {
    pthread_mutex_lock(&pool->lock);
    while (pool->pending > 0)
      pthread_cond_wait(&pool->done, &pool->lock);
    pthread_mutex_unlock(&pool->lock);
  }
}
