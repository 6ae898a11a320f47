/* The thread pool of render/thread_pool.h: workers sleep on a condition
 * variable between runs; a run bumps a generation counter and wakes them,
 * and the last worker to finish wakes the caller. */
#include "render/thread_pool.h"

#include "core/error.h"

#include <pthread.h>
#include <stdlib.h>

typedef struct pool_thread {
  thread_pool *pool;
  int index;
  pthread_t id;
} pool_thread;

struct thread_pool {
  pthread_mutex_t lock;
  pthread_cond_t wake, done;
  unsigned long generation; /* bumped by each run */
  int quit;
  int size;    /* workers, the caller included */
  int workers; /* of the current run */
  int pending; /* spawned workers of the current run still working */
  pool_task task;
  void *arg;
  pool_thread *threads; /* size - 1 spawned threads, indices 1.. */
};

static void *thread_main(void *p) {
  pool_thread *self = p;
  thread_pool *pool = self->pool;
  unsigned long seen = 0;
  pthread_mutex_lock(&pool->lock);
  for (;;) {
    while (!pool->quit && pool->generation == seen)
      pthread_cond_wait(&pool->wake, &pool->lock);
    if (pool->quit)
      break;
    seen = pool->generation;
    if (self->index >= pool->workers)
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
  pool_thread *t = threads > 1 ? calloc((size_t)threads - 1, sizeof *t) : NULL;
  if (!pool || (threads > 1 && !t)) {
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
    t[i - 1].pool = pool;
    t[i - 1].index = i;
    if (pthread_create(&t[i - 1].id, NULL, thread_main, &t[i - 1]) != 0)
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
  for (int i = 1; i < pool->size; i++)
    pthread_join(pool->threads[i - 1].id, NULL);
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
  if (workers > 1) {
    pthread_mutex_lock(&pool->lock);
    pool->task = task;
    pool->arg = arg;
    pool->workers = workers;
    pool->pending = workers - 1;
    pool->generation++;
    pthread_cond_broadcast(&pool->wake);
    pthread_mutex_unlock(&pool->lock);
  }
  task(arg, 0);
  if (workers > 1) {
    pthread_mutex_lock(&pool->lock);
    while (pool->pending > 0)
      pthread_cond_wait(&pool->done, &pool->lock);
    pthread_mutex_unlock(&pool->lock);
  }
}
