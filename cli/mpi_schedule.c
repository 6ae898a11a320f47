/* The master/worker schedule of glint-mpi (cli/mpi.h).
 *
 * Dynamic (the default): rank 0 hands each worker `in_flight` units at the
 * start and one more for each result it gets back, so a worker always has
 * its next unit queued while it renders and sends the last; rank 0 renders
 * units itself, on a thread of their own, while its main thread looks at
 * its mail. Static (the baseline): unit u belongs to rank u % size from the
 * start.
 *
 * Results travel as one message each, sent by the worker (MPI_Isend, from
 * one of `in_flight` buffers, so it renders the next unit while rank 0
 * collects) the moment a unit is done. Rank 0 only ever waits by polling
 * (MPI_Testsome and a short sleep), so that it notices a stop signal and a
 * worker that has gone silent: one that owes units and has sent nothing for
 * `timeout` seconds ends the job with a message naming it. A worker whose
 * unit fails sends its message to rank 0, which prints it and ends the job;
 * a rank that dies is noticed by mpirun, which ends the job itself (and
 * rank 0, stopped by its SIGTERM, leaves no partial file). */
#include "mpi.h"

#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { TAG_WORK = 1, TAG_RESULT, TAG_ERROR, TAG_DONE, TAG_BYE };
enum { STOP = -1 };

/* What precedes a result's pixels. */
typedef struct result_header {
  int32_t unit;
  int32_t reserved;
  uint64_t size; /* of the result after the header */
  double seconds;
} result_header;

/* A result message at its largest: the header, then the result (which
 * starts 8-byte aligned). */
static size_t result_bytes(const mpi_job *job) {
  return sizeof(result_header) + job->unit_bytes;
}

static void *result_of(unsigned char *buffer) {
  return buffer + sizeof(result_header);
}

static void sleep_seconds(double s) {
  if (s <= 0)
    return;
  struct timespec ts = {(time_t)s, (long)((s - (double)(time_t)s) * 1e9)};
  nanosleep(&ts, NULL);
}

/* How long a rank waiting for MPI sleeps between looks: rank 0, with
 * nothing come in, from the shortest, doubling, to the longest (a worker
 * holds two units or more, each longer than that, until the last are
 * handed out); a worker, always the shortest. Looking only every half
 * unit (up to 20 ms for frames) was tried: 48 frames on 16 ranks took
 * 0.69-0.72 s where 1 ms had given 0.57-0.58 s (on two machines of the
 * same kind), a large result reaching rank 0 only as it looks. */
#define PAUSE_SHORTEST 100e-6
#define PAUSE_LONGEST 1e-3
/* Rank 0 with no workers looks only for a stop signal, which also cancels
 * the unit it renders. */
#define PAUSE_ALONE 0.05

static void pause_briefly(void) { sleep_seconds(PAUSE_SHORTEST); }

/* A unit, timed, and slowed when a test asks for it. */
static int render_unit(mpi_job *job, int unit, void *result, size_t *size,
                       double *seconds, glint_error *error) {
  double t0 = cli_now();
  int r = job->render(job->context, unit, result, size, error);
  double t = cli_now() - t0;
  if (job->slow > 1)
    sleep_seconds((job->slow - 1) * t);
  *seconds = cli_now() - t0;
  return r;
}

/* ---- rank 0's own units -------------------------------------------------- */

/* Rank 0 renders its units on a thread of their own while its main thread,
 * the only one that calls MPI (MPI_THREAD_FUNNELED), goes on serving the
 * workers. When rank 0 rendered between its turns as the master, a worker
 * whose queue ran dry waited for rank 0's unit to end (a 1280x720 frame at
 * one thread takes 0.2 s): on 16 cores, one thread a rank, the workers
 * rendered 55-70% of the time (docs/mpi.md, "Scaling"). */
enum { OWN_IDLE, OWN_RENDERING, OWN_FINISHED };

typedef struct own_units {
  mpi_job *job;
  pthread_t thread;
  pthread_mutex_t lock;
  pthread_cond_t changed; /* state or quit */
  int state, quit;
  /* the unit, and once it is finished its outcome */
  int unit, status;
  double seconds;
  glint_error error;
} own_units;

static void *own_thread(void *arg) {
  own_units *o = arg;
  pthread_mutex_lock(&o->lock);
  for (;;) {
    while (!o->quit && o->state != OWN_RENDERING)
      pthread_cond_wait(&o->changed, &o->lock);
    if (o->quit)
      break;
    int unit = o->unit;
    pthread_mutex_unlock(&o->lock);
    glint_error error = {0};
    double seconds = 0;
    size_t size;
    int status = render_unit(o->job, unit, NULL, &size, &seconds, &error);
    pthread_mutex_lock(&o->lock);
    o->status = status;
    o->seconds = seconds;
    o->error = error;
    o->state = OWN_FINISHED;
    pthread_cond_broadcast(&o->changed);
  }
  pthread_mutex_unlock(&o->lock);
  return NULL;
}

/* mpi_world's settle: waits until the unit being rendered, cancelled by
 * the world's `ending`, has stopped. */
static void own_settle(void *context) {
  own_units *o = context;
  pthread_mutex_lock(&o->lock);
  while (o->state == OWN_RENDERING)
    pthread_cond_wait(&o->changed, &o->lock);
  pthread_mutex_unlock(&o->lock);
}

static void own_start(own_units *o, mpi_job *job) {
  memset(o, 0, sizeof *o);
  o->job = job;
  pthread_condattr_t attr;
  pthread_condattr_init(&attr);
  pthread_condattr_setclock(&attr, CLOCK_MONOTONIC);
  pthread_mutex_init(&o->lock, NULL);
  pthread_cond_init(&o->changed, &attr);
  pthread_condattr_destroy(&attr);
  if (pthread_create(&o->thread, NULL, own_thread, o))
    mpi_fail(job->world, 1, "cannot start a thread to render on");
  mpi_world *world = (mpi_world *)job->world;
  world->settle_context = o;
  world->settle = own_settle;
}

static void own_render(own_units *o, int unit) {
  pthread_mutex_lock(&o->lock);
  o->unit = unit;
  o->state = OWN_RENDERING;
  pthread_cond_broadcast(&o->changed);
  pthread_mutex_unlock(&o->lock);
}

/* OWN_IDLE, OWN_RENDERING, or OWN_FINISHED once when a unit is done (its
 * outcome then in o->status, o->seconds, o->error), after which it is
 * idle. */
static int own_state(own_units *o) {
  pthread_mutex_lock(&o->lock);
  int state = o->state;
  if (state == OWN_FINISHED)
    o->state = OWN_IDLE;
  pthread_mutex_unlock(&o->lock);
  return state;
}

/* Waits `seconds`, or less when the unit being rendered finishes first. */
static void own_wait(own_units *o, double seconds) {
  pthread_mutex_lock(&o->lock);
  if (o->state != OWN_RENDERING) { /* finished meanwhile: no wait */
    int idle = o->state == OWN_IDLE;
    pthread_mutex_unlock(&o->lock);
    if (idle)
      sleep_seconds(seconds);
    return;
  }
  struct timespec until;
  clock_gettime(CLOCK_MONOTONIC, &until);
  long ns = until.tv_nsec + (long)(seconds * 1e9);
  until.tv_sec += ns / 1000000000L;
  until.tv_nsec = ns % 1000000000L;
  pthread_cond_timedwait(&o->changed, &o->lock, &until);
  pthread_mutex_unlock(&o->lock);
}

static void own_stop(own_units *o) {
  mpi_world *world = (mpi_world *)o->job->world;
  world->settle = NULL;
  pthread_mutex_lock(&o->lock);
  o->quit = 1;
  pthread_cond_broadcast(&o->changed);
  pthread_mutex_unlock(&o->lock);
  pthread_join(o->thread, NULL);
  pthread_cond_destroy(&o->changed);
  pthread_mutex_destroy(&o->lock);
}

/* ---- rank 0 ------------------------------------------------------------- */

typedef struct master {
  mpi_job *job;
  int workers; /* size - 1; worker w is rank w + 1 */
  unsigned char **buffers;
  MPI_Request *requests; /* a posted receive per worker */
  int *indices;          /* MPI_Testsome's answer */
  int *owed;             /* units handed to the worker, not yet back */
  int *received;         /* results from the worker */
  int32_t *sent;         /* dynamic, at the end: results it says it sent */
  MPI_Request *byes;     /* ... received here */
  double *last_heard;
  unsigned char *taken; /* per unit: its result is in the output */
  int finishing;        /* dynamic: every unit is taken, workers told */
  char error_text[MPI_MESSAGE_CHARS];
  MPI_Request error_request;
  int next; /* dynamic: the next unit to hand out */
  int done;
} master;

static void post_receive(master *m, int w) {
  const mpi_world *world = m->job->world;
  mpi_check(world,
            MPI_Irecv(m->buffers[w], (int)result_bytes(m->job), MPI_BYTE, w + 1,
                      TAG_RESULT, world->comm, &m->requests[w]),
            "posting a receive");
}

static void send_unit(master *m, int w, int unit) {
  const mpi_world *world = m->job->world;
  int32_t u = unit;
  mpi_check(world, MPI_Send(&u, 1, MPI_INT32_T, w + 1, TAG_WORK, world->comm),
            "handing out work");
  if (unit != STOP)
    m->owed[w]++;
}

/* Whether rank 0 keeps unit u for itself (static schedule). */
static int is_mine(const mpi_job *job, int unit) {
  return unit % job->world->size == 0;
}

/* Takes what has arrived, hands out more, and checks on the workers;
 * returns how many results came in. */
static int serve(master *m) {
  mpi_job *job = m->job;
  const mpi_world *world = job->world;
  if (cli_stopped())
    mpi_fail(world, EXIT_INTERRUPTED, "%s", job->stopped_message);
  int flag = 0, arrived = 0;
  MPI_Status status;
  if (m->workers) { /* a worker's unit failed: its message */
    mpi_check(world, MPI_Test(&m->error_request, &flag, &status),
              "checking for errors");
    if (flag) {
      m->error_text[sizeof m->error_text - 1] = '\0';
      int r = status.MPI_SOURCE;
      mpi_fail(world, EXIT_USAGE, "rank %d (%s): %s", r, world->hosts[r],
               m->error_text);
    }
  }
  for (int count = 1; m->workers && count > 0;) {
    mpi_check(world,
              MPI_Testsome(m->workers, m->requests, &count, m->indices,
                           MPI_STATUSES_IGNORE),
              "collecting results");
    if (count == MPI_UNDEFINED)
      break;
    arrived += count;
    for (int i = 0; i < count; i++) {
      int w = m->indices[i];
      const result_header *h = (const result_header *)(void *)m->buffers[w];
      glint_error error = {0};
      m->received[w]++;
      m->last_heard[w] = cli_now();
      if (m->owed[w] > 0)
        m->owed[w]--;
      if (h->unit < 0 || h->unit >= job->units)
        mpi_fail(world, EXIT_USAGE, "rank %d (%s) sent %s %d, which is none",
                 w + 1, world->hosts[w + 1], job->noun, (int)h->unit);
      job->seconds_by_rank[w + 1] += h->seconds;
      if (m->taken[h->unit]) { /* rank 0 took it meanwhile (the tail) */
        post_receive(m, w);
        continue;
      }
      if (h->size > job->unit_bytes ||
          job->take(job->context, h->unit, w + 1, result_of(m->buffers[w]),
                    (size_t)h->size, &error)) {
        if (h->size > job->unit_bytes) {
          error.status = GLINT_E_PARSE;
          snprintf(error.message, sizeof error.message, "too large");
        }
        char name[64];
        job->name_of(job->context, h->unit, name, sizeof name);
        if (error.status == GLINT_E_IO) /* rank 0's own writing failed */
          mpi_fail(world, EXIT_USAGE, "%s (rank 0 writing %s, from rank %d)",
                   error.message, name, w + 1);
        mpi_fail(world, EXIT_USAGE, "%s, from rank %d (%s): %s", name, w + 1,
                 world->hosts[w + 1], error.message);
      }
      job->units_by_rank[w + 1]++;
      m->taken[h->unit] = 1;
      m->done++;
      if (job->dynamic && m->next < job->units)
        send_unit(m, w, m->next++);
      post_receive(m, w);
    }
  }
  for (int w = 0; m->finishing && w < m->workers; w++) {
    if (m->byes[w] == MPI_REQUEST_NULL)
      continue;
    mpi_check(world, MPI_Test(&m->byes[w], &flag, MPI_STATUS_IGNORE),
              "hearing from the workers");
    if (flag) /* it owes the results it sent that are still on their way */
      m->owed[w] = m->sent[w] - m->received[w];
  }
  double now = cli_now();
  for (int w = 0; w < m->workers; w++) {
    int awaited =
        m->owed[w] || (m->finishing && m->byes[w] != MPI_REQUEST_NULL);
    if (!awaited || now - m->last_heard[w] <= job->timeout)
      continue;
    if (m->finishing) { /* every unit is in: the output is whole */
      if (!job->silent_rank)
        job->silent_rank = w + 1;
      m->owed[w] = 0;
      MPI_Cancel(&m->byes[w]);
      MPI_Request_free(&m->byes[w]);
      continue;
    }
    if (job->dynamic) {
      /* Rank 0 renders what it holds (tail_unit), so nothing is lost: the
       * output is written whole, and the job ends naming the rank after
       * (mpi_end_if_silent). A result it sends later is taken or dropped
       * as any other. */
      fprintf(stderr,
              "glint-mpi: rank %d (%s) has sent nothing for %.0f s while it "
              "owes %d %s%s (is it hung? --timeout sets the limit); rank 0 "
              "renders them\n",
              w + 1, world->hosts[w + 1], job->timeout, m->owed[w], job->noun,
              m->owed[w] == 1 ? "" : "s");
      fflush(stderr);
      if (!job->silent_rank)
        job->silent_rank = w + 1;
      m->owed[w] = 0;
      continue;
    }
    mpi_fail(world, EXIT_USAGE,
             "rank %d (%s) has sent nothing for %.0f s while it owes %d "
             "%s%s (is it hung? --timeout sets the limit); ending the job",
             w + 1, world->hosts[w + 1], job->timeout, m->owed[w], job->noun,
             m->owed[w] == 1 ? "" : "s");
  }
  return arrived;
}

/* Dynamic, once every unit is handed out: rank 0, idle, renders a unit a
 * worker holds but has not returned, the last handed out first (the one
 * its worker will reach last), so that a slow worker's queue does not
 * decide when the job ends; whichever result comes first is taken, and
 * rendering being deterministic, both are the same. -1: none left. */
static int tail_unit(master *m) {
  for (int u = m->job->units; u-- > 0;)
    if (!m->taken[u])
      return u;
  return -1;
}

static void run_master(mpi_job *job) {
  const mpi_world *world = job->world;
  master m;
  memset(&m, 0, sizeof m);
  m.job = job;
  m.workers = world->size - 1;
  int n = m.workers ? m.workers : 1;
  m.buffers = calloc((size_t)n, sizeof *m.buffers);
  m.requests = calloc((size_t)n, sizeof *m.requests);
  m.owed = calloc((size_t)n, sizeof *m.owed);
  m.last_heard = calloc((size_t)n, sizeof *m.last_heard);
  m.indices = calloc((size_t)n, sizeof *m.indices);
  m.received = calloc((size_t)n, sizeof *m.received);
  m.sent = calloc((size_t)n, sizeof *m.sent);
  m.byes = calloc((size_t)n, sizeof *m.byes);
  m.taken = calloc((size_t)job->units + 1, 1);
  if (!m.buffers || !m.requests || !m.owed || !m.last_heard || !m.indices ||
      !m.received || !m.sent || !m.byes || !m.taken)
    mpi_fail(world, 1, "out of memory");
  double start = cli_now();
  for (int w = 0; w < m.workers; w++) {
    m.buffers[w] = malloc(result_bytes(job));
    if (!m.buffers[w])
      mpi_fail(world, 1, "out of memory for the results of rank %d", w + 1);
    m.last_heard[w] = start;
    post_receive(&m, w);
  }
  if (m.workers)
    mpi_check(world,
              MPI_Irecv(m.error_text, (int)sizeof m.error_text - 1, MPI_CHAR,
                        MPI_ANY_SOURCE, TAG_ERROR, world->comm,
                        &m.error_request),
              "posting a receive");
  if (job->dynamic) {
    for (int k = 0; k < job->in_flight; k++)
      for (int w = 0; w < m.workers && m.next < job->units; w++)
        send_unit(&m, w, m.next++);
  } else {
    for (int u = 0; u < job->units; u++)
      if (!is_mine(job, u))
        m.owed[u % world->size - 1]++;
  }
  own_units own;
  own_start(&own, job);
  double pause = PAUSE_SHORTEST;
  int mine = 0; /* static: rank 0's next unit */
  while (m.done < job->units) {
    int busy = 0, state = own_state(&own);
    if (state == OWN_FINISHED) {
      if (own.status) {
        if (cli_stopped())
          mpi_fail(world, EXIT_INTERRUPTED, "%s", job->stopped_message);
        char name[64];
        job->name_of(job->context, own.unit, name, sizeof name);
        mpi_fail(world, EXIT_USAGE, "%s: %s", name, own.error.message);
      }
      job->units_by_rank[0]++;
      job->seconds_by_rank[0] += own.seconds;
      m.done++;
      state = OWN_IDLE;
      busy = 1;
    }
    if (state == OWN_IDLE) {
      int unit = -1;
      if (job->dynamic && m.next < job->units)
        unit = m.next++;
      else if (job->dynamic)
        unit = tail_unit(&m);
      if (!job->dynamic) {
        while (mine < job->units && !is_mine(job, mine))
          mine++;
        if (mine < job->units)
          unit = mine++;
      }
      if (unit >= 0) { /* taken now: a worker's result for it is dropped */
        m.taken[unit] = 1;
        own_render(&own, unit);
        busy = 1;
      }
    }
    if (serve(&m))
      busy = 1;
    if (busy) {
      pause = PAUSE_SHORTEST;
    } else if (!m.workers) { /* nothing to serve: until the unit is done */
      own_wait(&own, PAUSE_ALONE);
    } else { /* back soon: at once when rank 0's own unit is done */
      own_wait(&own, pause);
      pause = pause * 2 < PAUSE_LONGEST ? pause * 2 : PAUSE_LONGEST;
    }
  }
  own_stop(&own);
  if (job->dynamic && m.workers) {
    /* Every unit is in: the workers skip what they still hold, say how
     * many results they sent, and those still on their way are
     * collected (and dropped). */
    m.finishing = 1;
    for (int w = 0; w < m.workers; w++) {
      int32_t nothing = 0;
      mpi_check(
          world,
          MPI_Send(&nothing, 1, MPI_INT32_T, w + 1, TAG_DONE, world->comm),
          "ending the work");
      send_unit(&m, w, STOP);
      mpi_check(world,
                MPI_Irecv(&m.sent[w], 1, MPI_INT32_T, w + 1, TAG_BYE,
                          world->comm, &m.byes[w]),
                "posting a receive");
    }
    for (;;) {
      int waiting = 0;
      for (int w = 0; w < m.workers; w++)
        waiting |= m.byes[w] != MPI_REQUEST_NULL ||
                   (m.received[w] < m.sent[w] && m.owed[w]);
      if (!waiting)
        break;
      pause_briefly();
      serve(&m);
    }
  }
  for (int w = 0; w < m.workers; w++) {
    MPI_Cancel(&m.requests[w]);
    MPI_Request_free(&m.requests[w]);
    free(m.buffers[w]);
  }
  if (m.workers) {
    MPI_Cancel(&m.error_request);
    MPI_Request_free(&m.error_request);
  }
  free(m.buffers);
  free(m.requests);
  free(m.owed);
  free(m.last_heard);
  free(m.indices);
  free(m.received);
  free(m.sent);
  free(m.byes);
  free(m.taken);
}

/* ---- the other ranks ---------------------------------------------------- */

/* The next unit from rank 0, or STOP; waits at most `timeout` seconds. */
static int next_unit(const mpi_job *job) {
  const mpi_world *world = job->world;
  int32_t unit;
  MPI_Request request;
  mpi_check(
      world,
      MPI_Irecv(&unit, 1, MPI_INT32_T, 0, TAG_WORK, world->comm, &request),
      "asking for work");
  double start = cli_now();
  for (;;) {
    int flag;
    mpi_check(world, MPI_Test(&request, &flag, MPI_STATUS_IGNORE),
              "waiting for work");
    if (flag)
      return unit;
    if (cli_now() - start > job->timeout)
      mpi_fail(world, EXIT_USAGE,
               "rank 0 (%s) has sent nothing for %.0f s (is it hung? "
               "--timeout sets the limit); ending the job",
               world->hosts[0], job->timeout);
    pause_briefly();
  }
}

/* Tells rank 0 why this rank cannot go on, and waits for the end. */
static void report_failure(const mpi_job *job, const char *message) {
  const mpi_world *world = job->world;
  char text[MPI_MESSAGE_CHARS];
  snprintf(text, sizeof text, "%s", message);
  mpi_check(world,
            MPI_Send(text, (int)strlen(text) + 1, MPI_CHAR, 0, TAG_ERROR,
                     world->comm),
            "reporting an error");
  sleep_seconds(job->timeout); /* rank 0 ends the job before */
  mpi_fail(world, EXIT_USAGE, "%s", message);
}

static void run_worker(mpi_job *job) {
  const mpi_world *world = job->world;
  /* Dynamic: a worker holds at most in_flight units, so that many results
   * can be on their way. Static: a worker renders on whatever rank 0 does,
   * and cheap units (sky) come far faster than rank 0, busy with an
   * expensive one, collects them: more results may wait to be collected
   * before the worker has to. */
  int buffers = job->in_flight * (job->dynamic ? 1 : 8);
  buffers = buffers < 2 ? 2 : buffers;
  unsigned char **buffer = calloc((size_t)buffers, sizeof *buffer);
  MPI_Request *sending = malloc((size_t)buffers * sizeof *sending);
  if (!buffer || !sending)
    mpi_fail(world, 1, "out of memory");
  for (int b = 0; b < buffers; b++) {
    sending[b] = MPI_REQUEST_NULL;
    if (!(buffer[b] = malloc(result_bytes(job))))
      mpi_fail(world, 1, "out of memory for %d %ss", buffers, job->noun);
  }
  int b = 0, static_unit = world->rank, finishing = 0;
  int32_t sent = 0;
  for (;;) {
    int unit;
    if (job->dynamic) {
      unit = next_unit(job);
    } else {
      unit = static_unit < job->units ? static_unit : STOP;
      static_unit += world->size;
    }
    if (unit == STOP)
      break;
    if (job->dynamic && !finishing) { /* every unit is in: skip the rest */
      mpi_check(
          world,
          MPI_Iprobe(0, TAG_DONE, world->comm, &finishing, MPI_STATUS_IGNORE),
          "checking for the end");
    }
    if (finishing)
      continue;
    /* This buffer's last result must be on its way before it is reused. */
    mpi_check(world, MPI_Wait(&sending[b], MPI_STATUS_IGNORE),
              "sending a result");
    result_header *h = (result_header *)(void *)buffer[b];
    glint_error error;
    size_t size = 0;
    if (render_unit(job, unit, result_of(buffer[b]), &size, &h->seconds,
                    &error)) {
      char text[MPI_MESSAGE_CHARS], name[64];
      job->name_of(job->context, unit, name, sizeof name);
      snprintf(text, sizeof text, "%s: %s", name, error.message);
      report_failure(job, text);
    }
    h->unit = unit;
    h->reserved = 0;
    h->size = size;
    size_t bytes = sizeof(result_header) + size;
    mpi_check(world,
              MPI_Isend(buffer[b], (int)bytes, MPI_BYTE, 0, TAG_RESULT,
                        world->comm, &sending[b]),
              "sending a result");
    sent++;
    b = (b + 1) % buffers;
  }
  if (job->dynamic) {
    int32_t nothing;
    mpi_check(world,
              MPI_Recv(&nothing, 1, MPI_INT32_T, 0, TAG_DONE, world->comm,
                       MPI_STATUS_IGNORE),
              "hearing the end");
    mpi_check(world, MPI_Send(&sent, 1, MPI_INT32_T, 0, TAG_BYE, world->comm),
              "saying how many results were sent");
  }
  mpi_check(world, MPI_Waitall(buffers, sending, MPI_STATUSES_IGNORE),
            "sending the last results");
  for (int k = 0; k < buffers; k++)
    free(buffer[k]);
  free(buffer);
  free(sending);
}

void mpi_end_if_silent(const mpi_job *job, const char *written) {
  const mpi_world *world = job->world;
  if (world->rank != 0 || !job->silent_rank)
    return;
  int r = job->silent_rank;
  fprintf(stderr,
          "glint-mpi: rank %d (%s) went silent for %.0f s (is it hung? "
          "--timeout sets the limit); every %s was in and %s was written "
          "whole; ending the job\n",
          r, world->hosts[r], job->timeout, job->noun, written);
  fflush(stderr);
  MPI_Abort(world->comm, EXIT_USAGE);
  exit(EXIT_USAGE);
}

void mpi_run(mpi_job *job) {
  if (job->world->rank == 0)
    run_master(job);
  else
    run_worker(job);
}
