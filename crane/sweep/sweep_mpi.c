/* The MPI engine of crane-sweep (sweep_engine.h): a queue of cases on rank 0, handed out one at
 * a time to the rank that asks. Built only when meson finds MPI (-DCRANE_SWEEP_MPI).
 *
 * Messages (MPI_COMM_WORLD; a rank's messages to another arrive in the order sent):
 *   worker -> 0   TAG_REQUEST  int 0        a slot of the worker is free: a case, please
 *                 TAG_ROW      sweep_row    a finished case (bytes: the ranks run one build)
 *                 TAG_DONE     int 0        no more requests, nothing running
 *   0 -> worker   TAG_CASE     long index   the answer to a request: a case, or -1 (no more)
 *                 TAG_ABORT    int signal   the sweep is stopped: stop the running cases
 *                 TAG_BYE      int 0        the answer to TAG_DONE (after any TAG_ABORT)
 * Rank 0 runs cases of its own besides (--jobs slots), polling its processes and the messages
 * in turn; it never blocks, so that a worker's request is answered within about 10 ms. */
#include "sweep_engine.h"

#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { TAG_REQUEST = 1, TAG_ROW, TAG_DONE, TAG_CASE, TAG_ABORT, TAG_BYE };

static void sleep_ms(int ms)
{
    struct timespec ts = {0, (long)ms * 1000000L};
    nanosleep(&ts, NULL);
}

/* Polls the slots: finished cases become rows, handed to emit. Returns the number of busy
 * slots; *events counts what happened. */
typedef void (*emit_fn)(sweep_run *r, const sweep_row *row);

static int poll_slots(sweep_run *r, sweep_proc *slots, int jobs, int stopping, int hard,
                      int *events, emit_fn emit)
{
    int busy = 0;
    for (int j = 0; j < jobs; j++) {
        sweep_proc *p = &slots[j];
        if (p->pid > 0 && stopping) sweep_proc_stop(p, stopping, hard);
        if (p->pid > 0 && sweep_proc_poll(p)) {
            sweep_row row;
            sweep_case_finish(r, p, &row);
            emit(r, &row);
            (*events)++;
        }
        busy += p->pid > 0;
    }
    return busy;
}

static sweep_proc *free_slot(sweep_proc *slots, int jobs)
{
    for (int j = 0; j < jobs; j++)
        if (slots[j].pid <= 0) return &slots[j];
    return NULL;
}

/* Starts case index in a free slot; a case that cannot start is a row at once. */
static void start_case(sweep_run *r, sweep_proc *p, long index, emit_fn emit)
{
    if (sweep_case_start(r, p, index) != 0) {
        sweep_row row;
        sweep_case_finish(r, p, &row);
        emit(r, &row);
    }
}

/* ------------------------------------------------------------------ rank 0 ---- */

static void emit_local(sweep_run *r, const sweep_row *row)
{
    sweep_record(r, row, 0);
}

static void master(sweep_run *r)
{
    int jobs = r->jobs, nworkers = r->size - 1, done = 0, stopping = 0, hard = 0;
    sweep_proc *slots = calloc((size_t)jobs, sizeof *slots);
    char *finished = calloc((size_t)r->size, 1);
    if (!slots || !finished) {
        fprintf(stderr, "crane-sweep: out of memory\n");
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    long next = 0;
    for (;;) {
        int events = 0;
        if (sweep_signal && !stopping) {
            stopping = (int)sweep_signal;
            int sig = stopping;
            for (int w = 1; w < r->size; w++)
                if (!finished[w]) MPI_Send(&sig, 1, MPI_INT, w, TAG_ABORT, MPI_COMM_WORLD);
        }
        if (sweep_signal_count > 1) hard = 1;
        /* the messages */
        for (;;) {
            int flag = 0;
            MPI_Status st;
            MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
            if (!flag) break;
            events++;
            int src = st.MPI_SOURCE, dummy;
            if (st.MPI_TAG == TAG_REQUEST) {
                MPI_Recv(&dummy, 1, MPI_INT, src, TAG_REQUEST, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
                long index = !stopping && next < r->nqueue ? r->queue[next++] : -1;
                if (index >= 0) r->nrun++;
                MPI_Send(&index, 1, MPI_LONG, src, TAG_CASE, MPI_COMM_WORLD);
            } else if (st.MPI_TAG == TAG_ROW) {
                sweep_row row;
                MPI_Recv(&row, (int)sizeof row, MPI_BYTE, src, TAG_ROW, MPI_COMM_WORLD,
                         MPI_STATUS_IGNORE);
                sweep_record(r, &row, src);
            } else if (st.MPI_TAG == TAG_DONE) {
                MPI_Recv(&dummy, 1, MPI_INT, src, TAG_DONE, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
                finished[src] = 1;
                done++;
                dummy = 0;
                MPI_Send(&dummy, 1, MPI_INT, src, TAG_BYE, MPI_COMM_WORLD);
            } else { /* not ours: take it off the queue */
                char buf[sizeof(sweep_row)];
                MPI_Recv(buf, (int)sizeof buf, MPI_BYTE, src, st.MPI_TAG, MPI_COMM_WORLD,
                         MPI_STATUS_IGNORE);
            }
        }
        /* rank 0's own cases */
        int busy = poll_slots(r, slots, jobs, stopping, hard, &events, emit_local);
        sweep_proc *p;
        while (!stopping && next < r->nqueue && (p = free_slot(slots, jobs)) != NULL) {
            r->nrun++;
            start_case(r, p, r->queue[next++], emit_local);
            busy += p->pid > 0;
            events++;
        }
        if (!busy && done == nworkers && (stopping || next >= r->nqueue)) break;
        if (!events) sleep_ms(10);
    }
    free(slots);
    free(finished);
}

/* ------------------------------------------------------------------ workers ---- */

static void emit_remote(sweep_run *r, const sweep_row *row)
{
    (void)r;
    MPI_Send((void *)row, (int)sizeof *row, MPI_BYTE, 0, TAG_ROW, MPI_COMM_WORLD);
}

static void worker(sweep_run *r)
{
    int jobs = r->jobs, pending = 0, no_more = 0, stopping = 0, hard = 0, aborted = 0;
    sweep_proc *slots = calloc((size_t)jobs, sizeof *slots);
    if (!slots) {
        fprintf(stderr, "crane-sweep: rank %d: out of memory\n", r->rank);
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    for (;;) {
        int events = 0;
        int sig = sweep_signal ? (int)sweep_signal : aborted;
        if (sig && !stopping) {
            stopping = sig;
            no_more = 1;
        }
        if (sweep_signal_count > 1) hard = 1;
        int busy = poll_slots(r, slots, jobs, stopping, hard, &events, emit_remote);
        while (!no_more && busy + pending < jobs) {
            int zero = 0;
            MPI_Send(&zero, 1, MPI_INT, 0, TAG_REQUEST, MPI_COMM_WORLD);
            pending++;
        }
        for (;;) {
            int flag = 0;
            MPI_Status st;
            MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
            if (!flag) break;
            events++;
            if (st.MPI_TAG == TAG_CASE) {
                long index;
                MPI_Recv(&index, 1, MPI_LONG, 0, TAG_CASE, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
                pending--;
                if (index < 0) {
                    no_more = 1;
                } else if (stopping) { /* handed out as the stop came: not started */
                    sweep_row row;
                    sweep_row_not_run(&row, index, "the sweep was stopped before the case started");
                    emit_remote(r, &row);
                } else {
                    sweep_proc *p = free_slot(slots, jobs);
                    start_case(r, p, index, emit_remote);
                    busy += p->pid > 0;
                }
            } else if (st.MPI_TAG == TAG_ABORT) {
                MPI_Recv(&aborted, 1, MPI_INT, 0, TAG_ABORT, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            } else {
                char buf[sizeof(sweep_row)];
                MPI_Recv(buf, (int)sizeof buf, MPI_BYTE, 0, st.MPI_TAG, MPI_COMM_WORLD,
                         MPI_STATUS_IGNORE);
            }
        }
        if (no_more && pending == 0 && busy == 0) break;
        if (!events) sleep_ms(10);
    }
    /* done: then wait for rank 0's goodbye, taking any abort that crossed our message */
    int zero = 0;
    MPI_Send(&zero, 1, MPI_INT, 0, TAG_DONE, MPI_COMM_WORLD);
    for (;;) {
        MPI_Status st;
        int v;
        MPI_Recv(&v, 1, MPI_INT, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
        if (st.MPI_TAG == TAG_BYE) break;
    }
    free(slots);
}

void sweep_engine_mpi(sweep_run *r)
{
    if (r->rank == 0)
        master(r);
    else
        worker(r);
}
