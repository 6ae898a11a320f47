/* The threads of core/thread.h. */
#define _GNU_SOURCE /* pthread_getattr_np */
#include "core/thread.h"

#include <stdint.h>

int gli_thread_start(pthread_t *id, void *(*run)(void *), void *arg) {
  pthread_attr_t attr;
  int err = pthread_attr_init(&attr);
  if (err)
    return err;
  err = pthread_attr_setstacksize(&attr, GLI_THREAD_STACK);
  if (!err)
    err = pthread_create(id, &attr, run, arg);
  pthread_attr_destroy(&attr);
  return err;
}

int gli_thread_can_render(void) {
  /* (for the main thread glibc reads /proc/self/maps: some 30 us) */
  pthread_attr_t attr;
  void *lowest;
  size_t size;
  if (pthread_getattr_np(pthread_self(), &attr) != 0)
    return 0;
  int err = pthread_attr_getstack(&attr, &lowest, &size);
  pthread_attr_destroy(&attr);
  char here;
  uintptr_t at = (uintptr_t)&here, bottom = (uintptr_t)lowest;
  return !err && at > bottom && at - bottom <= size &&
         at - bottom >= GLI_RENDER_STACK;
}
